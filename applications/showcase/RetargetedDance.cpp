#include "RetargetedDance.h"

#include <osgActor/ActorRetarget>
#include <osgActor/core/ClipPlayer>
#include <osgActor/mocap/MotionFile>

#include <osg/Notify>
#include <osgDB/FileUtils>
#include <osgDB/Options>

namespace osgActorShowcase {

namespace {

/** The path of a file in the database path or on osgDB's data path; empty, with a warning naming the file, when it
  * is not there. */
std::string findFile(const std::string& file, const std::string& databasePath, const char* what)
{
    osg::ref_ptr<osgDB::Options> options = new osgDB::Options;
    if (!databasePath.empty()) options->getDatabasePathList().push_back(databasePath);
    const std::string path = file.empty() ? std::string() : osgDB::findDataFile(file, options.get());
    if (path.empty())
        OSG_WARN << "osgActorShowcase::RetargetedDance: cannot find the " << what << " '" << file
                 << "' (in '" << databasePath << "' or on osgDB's data path); the actor keeps its own motion"
                 << std::endl;
    return path;
}

} // namespace

const char* const RetargetedDance::kControllerName = "retargeted dance";

RetargetedDance::RetargetedDance(const RetargetedDance& dance, const osg::CopyOp& copyop)
    : osg::Object(dance, copyop), osg::Callback(dance, copyop), ControllerRig(dance, copyop),
      _skeletonFile(dance._skeletonFile), _motionFile(dance._motionFile), _databasePath(dance._databasePath)
{
}

osgActor::RetargetClipOptions RetargetedDance::retargetOptions()
{
    osgActor::RetargetClipOptions options;
    options.name = "retargeted dance";
    options.ik = true; // the feet planted where the source's are
    return options;
}

bool RetargetedDance::rig(osgActor::ActorNode& actor) const
{
    const std::string skeleton = findFile(_skeletonFile, _databasePath, "skeleton file");
    const std::string motion = skeleton.empty() ? std::string() : findFile(_motionFile, _databasePath, "motion file");
    if (motion.empty()) return false;
    osgActor::MotionFileOptions fileOptions;
    fileOptions.skeletonFile = skeleton;
    const osgActor::MocapImport imported = osgActor::readMotionFile(motion, fileOptions);
    if (!imported || !imported.clip)
    {
        OSG_WARN << "osgActorShowcase::RetargetedDance: "
                 << (imported ? "'" + motion + "' holds no motion" : imported.error)
                 << "; the actor keeps its own motion" << std::endl;
        return false;
    }
    osgActor::RetargetSkeleton source;
    source.definition = imported.definition;
    const osgActor::RetargetClipResult retargeted =
        osgActor::retargetClipOntoActor(actor, source, *imported.clip, retargetOptions());
    if (!retargeted)
    {
        OSG_WARN << "osgActorShowcase::RetargetedDance: '" << motion << "': " << retargeted.error
                 << "; the actor keeps its own motion" << std::endl;
        return false;
    }

    // The dance replaces whatever the actor played (a rigged model's own clip, such as Cesium Man's walk).
    const std::vector<osgActor::ControllerPtr> controllers = actor.getControllers();
    for (const osgActor::ControllerPtr& controller : controllers)
        if (std::dynamic_pointer_cast<osgActor::ClipPlayer>(controller)) actor.removeController(controller);
    auto player = std::make_shared<osgActor::ClipPlayer>(retargeted.clip);
    player->setName(kControllerName);
    player->setPlayMode(osgActor::PlayMode::Loop);
    player->play();
    actor.addController(player);
    return true;
}

} // namespace osgActorShowcase
