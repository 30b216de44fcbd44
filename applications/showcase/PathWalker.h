/* osgActorShowcase: a humanoid walking along a stored path. */
#ifndef OSGACTORSHOWCASE_PATHWALKER_H
#define OSGACTORSHOWCASE_PATHWALKER_H 1

#include "ActorDriver.h"

#include <osg/AnimationPath>

namespace osgActorShowcase {

/** Walks the actors of its group along a path: the path (an osg::AnimationPath, so that it is stored with the
  * scene) places each actor's reference point (pre-transform: position, and the rotation that turns the actor's
  * forward direction, -Y, along the path), and the walk cycle (applyWalkCycle) moves the legs, one full cycle per
  * cycle duration. Make the path at the walking speed the cycle suits: stride length = speed x cycle duration. */
class OSGACTORSHOWCASE_EXPORT PathWalker : public ActorDriver
{
public:
    PathWalker();
    PathWalker(const PathWalker& walker, const osg::CopyOp& copyop = osg::CopyOp::SHALLOW_COPY);

    META_Object(osgActorShowcase, PathWalker);

    void setPath(osg::AnimationPath* path) { _path = path; }
    const osg::AnimationPath* getPath() const { return _path.get(); }
    /** Seconds per walk cycle (two steps), > 0. */
    void setCycleDuration(double seconds) { _cycleDuration = seconds; }
    double getCycleDuration() const { return _cycleDuration; }

    void drive(osgActor::ActorNode& actor, double time) override;

protected:
    ~PathWalker() override = default;

    osg::ref_ptr<osg::AnimationPath> _path;
    double _cycleDuration;
};

} // namespace osgActorShowcase

#endif
