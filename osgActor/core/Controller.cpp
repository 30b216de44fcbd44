#include <osgActor/core/Controller>

#include <glm/ext/scalar_constants.hpp>

#include <algorithm>
#include <cmath>

namespace osgActor {

DofSelection DofSelection::joints(const ActorDefinition& definition, const std::vector<std::string>& jointNames,
                                  bool withDescendants, std::string* error)
{
    DofSelection selection;
    const unsigned numJoints = definition.getNumJoints();
    std::vector<bool> chosen(numJoints, false);
    for (const std::string& name : jointNames)
    {
        const int joint = definition.findJoint(name);
        if (joint < 0)
        {
            if (error) *error = "no joint named '" + name + "' in actor '" + definition.getName() + "'";
            return DofSelection();
        }
        chosen[static_cast<unsigned>(joint)] = true;
    }
    // Parents come first, so one pass carries a choice down to every descendant.
    if (withDescendants)
        for (unsigned j = 0; j < numJoints; ++j)
            if (definition.getParent(j) >= 0 && chosen[static_cast<unsigned>(definition.getParent(j))])
                chosen[j] = true;
    selection._weights.assign(definition.getNumDofs(), 0.0f);
    for (unsigned d = 0; d < definition.getNumDofs(); ++d)
        if (chosen[definition.getDofJoint(d)]) selection._weights[d] = 1.0f;
    return selection;
}

void DofSelection::setWeight(unsigned numDofs, unsigned dof, double weight)
{
    if (_weights.empty()) _weights.assign(numDofs, 0.0f);
    if (dof < _weights.size() && std::isfinite(weight))
        _weights[dof] = static_cast<float>(std::min(1.0, std::max(0.0, weight)));
}

void Controller::setWeight(double weight)
{
    if (std::isfinite(weight)) _weight = std::min(1.0, std::max(0.0, weight));
}

double blendAngle(double a, double b, double t)
{
    const double twoPi = 2.0 * glm::pi<double>();
    double delta = std::remainder(b - a, twoPi); // in [-pi, pi]
    return a + t * delta;
}

bool Controller::blendDof(ActorPose& pose, unsigned dof, double value, double w) const
{
    if (!(w > 0.0) || dof >= pose.getNumDofs()) return false;
    const double current = pose.getDof(dof);
    const double blended = isRotation(pose.getDefinition()->getDofType(dof)) ? blendAngle(current, value, w)
                                                                              : current + w * (value - current);
    return succeeded(pose.setDof(dof, blended));
}

bool runControllers(const std::vector<ControllerPtr>& controllers, const ControllerContext& context,
                    ControllerTarget& target)
{
    bool ran = false;
    for (const ControllerPtr& controller : controllers)
    {
        if (!controller || !controller->getEnabled() || controller->getWeight() <= 0.0) continue;
        controller->update(context, target);
        ran = true;
    }
    return ran;
}

} // namespace osgActor
