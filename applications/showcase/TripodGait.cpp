#include "TripodGait.h"
#include "TripodGaitController.h"

#include <osg/Notify>

namespace osgActorShowcase {

TripodGait::TripodGait() : _cycleDuration(0.8), _stepHeight(0.08) {}

TripodGait::TripodGait(const TripodGait& gait, const osg::CopyOp& copyop)
    : osg::Object(gait, copyop), osg::Callback(gait, copyop), ControllerRig(gait, copyop), _path(gait._path),
      _cycleDuration(gait._cycleDuration), _stepHeight(gait._stepHeight)
{
}

const char* TripodGait::getRigControllerName() const { return TripodGaitController::kControllerName; }

bool TripodGait::rig(osgActor::ActorNode& actor) const
{
    const char* const what = "osgActorShowcase::TripodGait: ";
    if (!_path)
    {
        OSG_WARN << what << "no path to walk, nothing to drive" << std::endl;
        return false;
    }
    TripodGaitController::LegChains chains;
    for (unsigned leg = 0; leg < TripodGaitController::kNumLegs; ++leg)
    {
        chains[leg] = actor.findIkChain(TripodGaitController::legChainName(leg));
        if (!chains[leg])
        {
            OSG_WARN << what << "actor '" << actor.getName() << "' has no IK chain '"
                     << TripodGaitController::legChainName(leg)
                     << "' (data/insect.actor gives each leg one, from the coxa to the foot), so it cannot walk"
                     << std::endl;
            return false;
        }
    }
    auto gait = std::make_shared<TripodGaitController>(_path, chains);
    if (!gait->setCycleDuration(_cycleDuration) || !gait->setStepHeight(_stepHeight))
    {
        OSG_WARN << what << "the cycle duration must be positive and the step height not negative" << std::endl;
        return false;
    }
    actor.addController(gait);
    return true;
}

} // namespace osgActorShowcase
