/* osgActorShowcase: a humanoid walking along a stored path. */
#ifndef OSGACTORSHOWCASE_PATHWALKER_H
#define OSGACTORSHOWCASE_PATHWALKER_H 1

#include "ControllerRig.h"

#include <osgActor/core/Trajectory>

namespace osgActorShowcase {

/** Walks the actors of its group along a stored path (an osgActor::Trajectory, stored with the scene): each actor
  * gets a TrajectoryPlayer that loops the path on its reference point (the pre-transform: position, and the heading
  * that turns the actor's forward direction, -Y, along the path), and, unless it plays a clip of its own (a rigged
  * model's walk, such as Cesium Man's), a ClipPlayer that loops the procedural walk cycle (makeWalkCycleClip()), one
  * full cycle per cycle duration. Make the path at the walking speed the walk suits: for the procedural cycle,
  * stride length = speed x cycle duration; for an actor's own clip, the speed at which its planted feet stay put. */
class OSGACTORSHOWCASE_EXPORT PathWalker : public ControllerRig
{
public:
    PathWalker();
    PathWalker(const PathWalker& walker, const osg::CopyOp& copyop = osg::CopyOp::SHALLOW_COPY);

    META_Object(osgActorShowcase, PathWalker);

    void setPath(osgActor::TrajectoryPtr path) { _path = std::move(path); }
    const osgActor::TrajectoryPtr& getPath() const { return _path; }
    /** Seconds per walk cycle (two steps), > 0. */
    void setCycleDuration(double seconds) { _cycleDuration = seconds; }
    double getCycleDuration() const { return _cycleDuration; }

    /** The controllers' names: the path's player (which marks a rigged actor) and the walk's. */
    static const char* const kPathControllerName;
    static const char* const kWalkControllerName;

    const char* getRigControllerName() const override { return kPathControllerName; }
    /** Adds the path's TrajectoryPlayer and, for an actor with the walk's joints and no clip of its own, the walk
      * cycle's ClipPlayer. An actor read from a file may play them already: a walk cycle under the walk's name is
      * kept as it is, and a path player a file's trajectory shorthand made (named after the trajectory,
      * findKeptPathPlayer()) is taken and named as the rig names it, so the actor does not play two copies of
      * either. (An actor written after it was rigged comes back with both players under the rig's names, so it
      * counts as rigged.) */
    bool rig(osgActor::ActorNode& actor) const override;

protected:
    ~PathWalker() override = default;

    /** True when the actor has a ClipPlayer not named as the rig's walk cycle (its own motion). */
    static bool playsOwnClip(const osgActor::ActorNode& actor);
    /** The actor's TrajectoryPlayer of a trajectory named as this rig's path (one a file kept), or null. */
    std::shared_ptr<osgActor::TrajectoryPlayer> findKeptPathPlayer(const osgActor::ActorNode& actor) const;

    osgActor::TrajectoryPtr _path;
    double _cycleDuration;
};

} // namespace osgActorShowcase

#endif
