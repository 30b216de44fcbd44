/* osgActorShowcase: the paper's cockroach: a six-legged insect walking a stored path with a tripod gait. */
#ifndef OSGACTORSHOWCASE_TRIPODGAIT_H
#define OSGACTORSHOWCASE_TRIPODGAIT_H 1

#include "ActorDriver.h"
#include "InsectLeg.h"

#include <osg/AnimationPath>

#include <vector>

namespace osgActorShowcase {

/** Moves the insects of its group (data/insect.actor) along a stored trajectory with a tripod gait whose feet are
  * planted by inverse kinematics:
  * - the trajectory (an osg::AnimationPath, stored with the scene: the paper replays a behaviour simulator's path)
  *   places the body (pre-transform; the insect's head, -Y, turned along the path);
  * - the legs move in two tripods (left front, right middle, left hind; and the other three), each on the ground
  *   for half a cycle and swinging for the other half;
  * - a foot on the ground stays where it was put down: at the leg's rest position under the body as the body will
  *   be half-way through that stance, so the body walks over planted feet; a swinging foot moves to its next
  *   foothold on an arc of the step height;
  * - each leg's coxa, femur and tibia angles are solved (InsectLeg::solve) to put the foot's tip on its target.
  * Everything is a function of time, so any frame can be rendered alone. */
class OSGACTORSHOWCASE_EXPORT TripodGait : public ActorDriver
{
public:
    TripodGait();
    TripodGait(const TripodGait& gait, const osg::CopyOp& copyop = osg::CopyOp::SHALLOW_COPY);

    META_Object(osgActorShowcase, TripodGait);

    void setPath(osg::AnimationPath* path) { _path = path; }
    const osg::AnimationPath* getPath() const { return _path.get(); }
    /** Seconds per gait cycle (each tripod steps once), > 0. */
    void setCycleDuration(double seconds) { _cycleDuration = seconds; }
    double getCycleDuration() const { return _cycleDuration; }
    /** How high a swinging foot lifts, model units. */
    void setStepHeight(double height) { _stepHeight = height; }
    double getStepHeight() const { return _stepHeight; }
    /** Length of the tibia to the tip of the foot, model units (a property of the tibia's geometry). */
    void setTibiaReach(double reach) { _tibiaReach = reach; }
    double getTibiaReach() const { return _tibiaReach; }

    void drive(osgActor::ActorNode& actor, double time) override;

    /** Where a leg's foot should be at a time, in the actor's parent frame (the path's frame); restFoot is the
      * foot's rest position in the actor's frame. Public for the tests. */
    osg::Vec3d footTarget(unsigned legIndex, const osg::Vec3d& restFoot, double time) const;
    /** The body's pose (the actor's pre-transform) at a time. */
    osg::Matrixd bodyMatrix(double time) const;

    /** The legs in gait order: tripod A (l_front, r_middle, l_hind), then tripod B (r_front, l_middle, r_hind). */
    static const char* const kLegNames[6];

protected:
    ~TripodGait() override = default;

    osg::ref_ptr<osg::AnimationPath> _path;
    double _cycleDuration;
    double _stepHeight;
    double _tibiaReach;
};

} // namespace osgActorShowcase

#endif
