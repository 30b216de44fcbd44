#include <osgActor/core/ik/IkController>
#include <osgActor/core/ik/IkSolve>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/matrix.hpp>

namespace osgActor {

IkController::IkController(IkChainPtr chain) { setChain(std::move(chain)); }

void IkController::setChain(IkChainPtr chain)
{
    _chain = std::move(chain);
    _checkedDefinition = nullptr;
    if (!_chain) return;
    _workspace.resize(*_chain);
    if (getName().empty()) setName(_chain->getName());
}

bool IkController::setGoal(const IkGoal& goal, IkGoalSpace space)
{
    if (!goal.isValid()) return false;
    _goal = goal;
    _space = space;
    _hasGoal = true;
    return true;
}

void IkController::update(const ControllerContext& context, ControllerTarget& target)
{
    ActorPose& pose = target.pose;
    const ActorDefinition* definition = pose.getDefinition().get();
    if (!_chain || !_hasGoal || !definition) return;
    if (definition != _checkedDefinition)
    {
        if (!_chain->fits(*definition)) return;
        _checkedDefinition = definition;
    }

    // The pose as the controllers before this one left it, so the chain starts from (and its root hangs off) the
    // frame being built.
    pose.updateMatrices();
    _lastModelGoal = _goal;
    if (_space == IkGoalSpace::World)
    {
        // world -> model: the inverse of (actor's parent in world) * actor_m, from this frame's transforms.
        const glm::dmat4 worldToModel = glm::inverse(context.parentToWorld * computeActorMatrix(target.transforms));
        glm::dmat3 rotation(worldToModel);
        for (unsigned c = 0; c < 3; ++c) rotation[c] = glm::normalize(rotation[c]); // drop any scale above the actor
        _lastModelGoal.position = glm::dvec3(worldToModel * glm::dvec4(_goal.position, 1.0));
        _lastModelGoal.pole = glm::dvec3(worldToModel * glm::dvec4(_goal.pole, 1.0));
        _lastModelGoal.orientation = glm::quat_cast(rotation) * glm::normalize(_goal.orientation);
        if (!_lastModelGoal.isValid()) return; // a singular world matrix
    }

    _solveDofs = pose.getDofs();
    for (unsigned d = 0; d < _chain->getNumDofs(); ++d)
        _workspace.frozen[d] = effectiveWeight(_chain->getDof(d).dof) > 0.0 ? 0 : 1;
    IkJob job;
    job.definition = definition;
    job.chain = _chain.get();
    job.goal = &_lastModelGoal;
    const int parent = definition->getParent(_chain->getRootJoint());
    job.rootParentModel = parent >= 0 ? pose.getModelMatrix(static_cast<unsigned>(parent)) : glm::dmat4(1.0);
    job.jointModels = &pose.getModelMatrix(0); // current: updateMatrices() above
    job.dofs = _solveDofs.data();
    job.workspace = &_workspace;
    if (!solveIk(job)) return;
    _lastResult = job.result;
    for (const IkChainDof& d : _chain->getDofs()) writeDof(pose, d.dof, _solveDofs[d.dof]);
}

std::shared_ptr<Controller> IkController::cloneController() const
{
    return std::make_shared<IkController>(*this);
}

} // namespace osgActor
