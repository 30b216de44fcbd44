/* osgActorShowcase: the paper's cockroach: six-legged insects walking a stored path with a tripod gait. */
#ifndef OSGACTORSHOWCASE_TRIPODGAIT_H
#define OSGACTORSHOWCASE_TRIPODGAIT_H 1

#include "ControllerRig.h"

#include <osgActor/core/Trajectory>

namespace osgActorShowcase {

/** Walks the six-legged actors of its group (data/insect.actor) along a stored path (an osgActor::Trajectory,
  * stored with the scene: the paper replays a behaviour simulator's path) with a tripod gait whose feet are planted
  * by the library's leg IK: each actor gets a TripodGaitController on the path, solving the actor's own IK chains
  * "<leg>_leg" (TripodGaitController::legChainName()). An actor without those chains is refused with a warning. */
class OSGACTORSHOWCASE_EXPORT TripodGait : public ControllerRig
{
public:
    TripodGait();
    TripodGait(const TripodGait& gait, const osg::CopyOp& copyop = osg::CopyOp::SHALLOW_COPY);

    META_Object(osgActorShowcase, TripodGait);

    void setPath(osgActor::TrajectoryPtr path) { _path = std::move(path); }
    const osgActor::TrajectoryPtr& getPath() const { return _path; }
    /** Seconds per gait cycle (each tripod steps once), > 0. */
    void setCycleDuration(double seconds) { _cycleDuration = seconds; }
    double getCycleDuration() const { return _cycleDuration; }
    /** How high a swinging foot lifts, model units of the path's frame. */
    void setStepHeight(double height) { _stepHeight = height; }
    double getStepHeight() const { return _stepHeight; }

    const char* getRigControllerName() const override;
    /** Adds a TripodGaitController built on the actor's leg chains. */
    bool rig(osgActor::ActorNode& actor) const override;

protected:
    ~TripodGait() override = default;

    osgActor::TrajectoryPtr _path;
    double _cycleDuration;
    double _stepHeight;
};

} // namespace osgActorShowcase

#endif
