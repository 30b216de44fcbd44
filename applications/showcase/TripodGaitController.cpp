#include "TripodGaitController.h"

#include <glm/ext/quaternion_trigonometric.hpp>
#include <glm/ext/scalar_constants.hpp>

#include <cmath>

namespace osgActorShowcase {

const char* const TripodGaitController::kControllerName = "tripod gait";
const char* const TripodGaitController::kLegNames[kNumLegs] = {"l_front", "r_middle", "l_hind",
                                                               "r_front", "l_middle", "r_hind"};

namespace {

/** Tripod B steps half a cycle after tripod A. */
double legLag(unsigned leg) { return leg < 3 ? 0.0 : 0.5; }

} // namespace

TripodGaitController::TripodGaitController(osgActor::TrajectoryPtr path, const LegChains& legChains)
    : _body(std::move(path))
{
    setName(kControllerName);
    _body.setPlayMode(osgActor::PlayMode::Loop);
    for (unsigned leg = 0; leg < kNumLegs; ++leg) _legs[leg].setChain(legChains[leg]);
}

bool TripodGaitController::setCycleDuration(double seconds)
{
    if (!(seconds > 0.0) || !std::isfinite(seconds)) return false;
    _cycleDuration = seconds;
    return true;
}

bool TripodGaitController::setStepHeight(double height)
{
    if (!(height >= 0.0) || !std::isfinite(height)) return false;
    _stepHeight = height;
    return true;
}

bool TripodGaitController::isInStance(unsigned leg, double playTime) const
{
    const double u = playTime / _cycleDuration + legLag(leg);
    return u - std::floor(u) < 0.5;
}

glm::dvec3 TripodGaitController::foothold(unsigned leg, double step) const
{
    // The body where the path puts it a quarter cycle into the step (mid-stance), with this frame's post-transform.
    const double playTime = (step + 0.25 - legLag(leg)) * _cycleDuration;
    const osgActor::TrajectoryKey key = _body.getTrajectory()->sample(_body.pathTimeAt(playTime), _pathCursor);
    osgActor::ActorTransforms body = _transforms;
    body.preTranslation = key.position;
    body.preRotation = glm::angleAxis(key.heading, glm::dvec3(0.0, 0.0, 1.0));
    return glm::dvec3(osgActor::computeActorMatrix(body) * glm::dvec4(_restFeet[leg], 1.0));
}

glm::dvec3 TripodGaitController::footTarget(unsigned leg, double playTime) const
{
    // u counts this leg's steps; in each, half stance then half swing.
    const double u = playTime / _cycleDuration + legLag(leg);
    const double step = std::floor(u);
    const double within = u - step;
    if (within < 0.5) return foothold(leg, step);
    const double s = (within - 0.5) * 2.0;        // 0..1 through the swing
    const double eased = s * s * (3.0 - 2.0 * s); // leaves and lands softly
    glm::dvec3 foot = foothold(leg, step) * (1.0 - eased) + foothold(leg, step + 1.0) * eased;
    foot.z += _stepHeight * std::sin(glm::pi<double>() * s);
    return foot;
}

bool TripodGaitController::bindRestFeet(const osgActor::ActorDefinitionPtr& definition)
{
    if (definition.get() == _restFeetDefinition) return true;
    for (const osgActor::IkController& leg : _legs)
        if (!leg.getChain() || !leg.getChain()->fits(*definition)) return false;
    osgActor::ActorPose rest(definition); // the default pose
    rest.updateMatrices();
    for (unsigned leg = 0; leg < kNumLegs; ++leg)
    {
        const osgActor::IkChain& chain = *_legs[leg].getChain();
        _restFeet[leg] = glm::dvec3(rest.getModelMatrix(chain.getEffectorJoint()) *
                                    glm::dvec4(chain.getEffectorOffset(), 1.0));
    }
    _restFeetDefinition = definition.get();
    return true;
}

void TripodGaitController::update(const osgActor::ControllerContext& context, osgActor::ControllerTarget& target)
{
    if (!_body.getTrajectory()) return;
    _body.update(context, target); // the body first: the legs' world goals convert with this frame's actor matrix
    const osgActor::ActorDefinitionPtr& definition = target.pose.getDefinition();
    if (!definition || !bindRestFeet(definition)) return;
    _transforms = target.transforms;

    const double time = _body.getPlayTime();
    for (unsigned leg = 0; leg < kNumLegs; ++leg)
    {
        osgActor::IkGoal goal;
        goal.position = glm::dvec3(context.parentToWorld * glm::dvec4(footTarget(leg, time), 1.0)); // world space
        osgActor::IkController& solver = _legs[leg];
        solver.setWeight(getWeight());
        solver.setSelection(getSelection());
        if (solver.setGoal(goal, osgActor::IkGoalSpace::World)) solver.update(context, target);
    }
}

std::shared_ptr<osgActor::Controller> TripodGaitController::cloneController() const
{
    return std::make_shared<TripodGaitController>(*this);
}

} // namespace osgActorShowcase
