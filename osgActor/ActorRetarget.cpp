#include <osgActor/ActorRetarget>
#include <osgActor/ActorSceneIO>
#include <osgActor/io/JointMapSection>

#include <osg/Notify>

#include <sstream>

namespace osgActor {

JointMap getActorJointMap(const ActorNode& actor)
{
    std::string text;
    if (!actor.getUserValue(kSectionsUserValue, text) || text.empty()) return JointMap();
    std::istringstream in(text);
    std::vector<SyntaxStatement> sections;
    std::string error;
    ActorJointMaps maps;
    if (!parseSyntax(in, actor.getName(), sections, error) ||
        !readActorJointMaps(sections, actor.getName(), maps, error))
    {
        OSG_WARN << "osgActor: actor '" << actor.getName() << "': its joint map is broken (" << error
                 << "); guessing one" << std::endl;
        return JointMap();
    }
    return maps.own;
}

RetargetClipResult retargetClipOntoActor(ActorNode& actor, const RetargetSkeleton& source, const Clip& clip,
                                         const RetargetClipOptions& options, const RetargetOptions& rigOptions)
{
    RetargetSkeleton target;
    target.definition = actor.getDefinition();
    target.map = getActorJointMap(actor);
    const RetargetRigBuildResult rig = buildRetargetRig(source, target, rigOptions);
    if (!rig)
    {
        RetargetClipResult failed;
        failed.error = "retargeting clip '" + clip.getName() + "' onto actor '" + actor.getName() + "': " + rig.error;
        return failed;
    }
    RetargetClipResult result = retargetClip(*rig.rig, clip, options);
    if (!result) return result;
    if (!actor.getClipLibrary()) actor.setClipLibrary(std::make_shared<ClipLibrary>());
    actor.getClipLibrary()->addClip(result.clip);
    return result;
}

} // namespace osgActor
