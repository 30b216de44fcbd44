#include "PathWalker.h"
#include "WalkCycle.h"

namespace osgActorShowcase {

PathWalker::PathWalker() : _cycleDuration(1.1) {}

PathWalker::PathWalker(const PathWalker& walker, const osg::CopyOp& copyop)
    : osg::Object(walker, copyop), osg::Callback(walker, copyop), ActorDriver(walker, copyop), _path(walker._path), _cycleDuration(walker._cycleDuration)
{
}

void PathWalker::drive(osgActor::ActorNode& actor, double time)
{
    if (_path.valid() && !_path->empty())
    {
        osg::AnimationPath::ControlPoint point;
        if (_path->getInterpolatedControlPoint(time, point))
        {
            actor.setPreTranslation(point.getPosition());
            actor.setPreRotation(point.getRotation());
        }
    }
    if (_cycleDuration > 0.0) applyWalkCycle(actor, time / _cycleDuration);
}

} // namespace osgActorShowcase
