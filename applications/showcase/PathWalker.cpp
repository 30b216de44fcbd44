#include "PathWalker.h"
#include "WalkCycle.h"

#include <osgActor/core/ClipPlayer>

#include <osg/Notify>

namespace osgActorShowcase {

const char* const PathWalker::kPathControllerName = "walk path";
const char* const PathWalker::kWalkControllerName = "walk cycle";

PathWalker::PathWalker() : _cycleDuration(1.1) {}

PathWalker::PathWalker(const PathWalker& walker, const osg::CopyOp& copyop)
    : osg::Object(walker, copyop), osg::Callback(walker, copyop), ControllerRig(walker, copyop), _path(walker._path),
      _cycleDuration(walker._cycleDuration)
{
}

std::shared_ptr<osgActor::TrajectoryPlayer> PathWalker::findKeptPathPlayer(const osgActor::ActorNode& actor) const
{
    // A file written before players kept their names has the path's player under the trajectory's name.
    for (const osgActor::ControllerPtr& controller : actor.getControllers())
    {
        auto player = std::dynamic_pointer_cast<osgActor::TrajectoryPlayer>(controller);
        if (player && player->getTrajectory() && player->getTrajectory()->getName() == _path->getName())
            return player;
    }
    return nullptr;
}

bool PathWalker::playsOwnClip(const osgActor::ActorNode& actor)
{
    for (const osgActor::ControllerPtr& controller : actor.getControllers())
        if (std::dynamic_pointer_cast<osgActor::ClipPlayer>(controller)) return true;
    return false;
}

bool PathWalker::rig(osgActor::ActorNode& actor) const
{
    if (!_path || !actor.getDefinition())
    {
        OSG_WARN << "osgActorShowcase::PathWalker: " << (_path ? "an actor without a definition" : "no path to walk")
                 << ", nothing to drive" << std::endl;
        return false;
    }
    if (std::shared_ptr<osgActor::TrajectoryPlayer> kept = findKeptPathPlayer(actor))
        kept->setName(kPathControllerName);
    else
    {
        auto path = std::make_shared<osgActor::TrajectoryPlayer>(_path);
        path->setName(kPathControllerName);
        path->setPlayMode(osgActor::PlayMode::Loop);
        actor.addController(path);
    }

    // A file keeps clip players with their names and state; an actor that plays a clip of its own (a rigged model's
    // walk, readRiggedModelActor's "clip") walks with it rather than with the procedural cycle.
    if (std::dynamic_pointer_cast<osgActor::ClipPlayer>(actor.findController(kWalkControllerName))) return true;
    if (playsOwnClip(actor)) return true;
    // An actor without legs still follows the path.
    const osgActor::ClipBuildResult walk = makeWalkCycleClip(*actor.getDefinition(), _cycleDuration);
    if (!walk)
    {
        OSG_WARN << "osgActorShowcase::PathWalker: " << walk.error << std::endl;
        return true;
    }
    auto cycle = std::make_shared<osgActor::ClipPlayer>(walk.clip);
    cycle->setName(kWalkControllerName);
    cycle->setPlayMode(osgActor::PlayMode::Loop);
    actor.addController(cycle);
    return true;
}

} // namespace osgActorShowcase
