#include <osgActor/io/ClipRetarget>
#include <osgActor/core/retarget/RetargetClip>
#include <osgActor/io/JointMapSection>

namespace osgActor {

bool readClipRetarget(const SyntaxStatement& s, const std::string& fileName, ClipRetarget& retarget,
                      std::string& error)
{
    const std::string where = fileName + ":" + std::to_string(s.line) + ": ";
    if (s.arguments.size() != 1)
    {
        error = where + "'retarget' takes 'auto' or the name of a jointmap section";
        return false;
    }
    retarget.enabled = true;
    retarget.line = s.line;
    retarget.sourceMap = s.arguments[0].text == "auto" && !s.arguments[0].quoted ? std::string() : s.arguments[0].text;
    for (const SyntaxStatement& c : s.children)
    {
        const std::string at = fileName + ":" + std::to_string(c.line) + ": ";
        if (c.keyword != "ik")
        {
            error = at + "unknown keyword '" + c.keyword + "' in 'retarget' (ik)";
            return false;
        }
        if (c.hasBlock || c.arguments.size() != 1 || (c.arguments[0].text != "on" && c.arguments[0].text != "off"))
        {
            error = at + "'ik' takes on or off";
            return false;
        }
        retarget.ik = c.arguments[0].text == "on";
    }
    return true;
}

void writeClipRetarget(SyntaxWriter& writer, const ClipRetarget& retarget)
{
    writer.begin("retarget");
    if (retarget.sourceMap.empty()) writer.word("auto");
    else writer.name(retarget.sourceMap);
    if (!retarget.ik) writer.begin("ik").word("off").end();
    writer.end();
}

ClipPtr retargetClipForActor(const MocapImport& imported, const ActorDefinitionPtr& actor,
                             const ClipRetarget& retarget, const std::vector<SyntaxStatement>& sections,
                             const std::string& fileName, std::string& error)
{
    ActorJointMaps maps;
    if (!readActorJointMaps(sections, fileName, maps, error)) return nullptr;
    RetargetSkeleton source, target;
    source.definition = imported.definition;
    target.definition = actor;
    if (!retarget.sourceMap.empty())
    {
        const auto found = maps.named.find(retarget.sourceMap);
        if (found == maps.named.end())
        {
            error = "retargeting: no jointmap section named '" + retarget.sourceMap + "'";
            return nullptr;
        }
        source.map = found->second;
    }
    if (maps.hasOwn) target.map = maps.own;
    const RetargetRigBuildResult rig = buildRetargetRig(source, target);
    if (!rig)
    {
        error = "retargeting: " + rig.error;
        return nullptr;
    }
    RetargetClipOptions options;
    options.ik = retarget.ik;
    const RetargetClipResult result = retargetClip(*rig.rig, *imported.clip, options);
    if (!result) error = "retargeting: " + result.error;
    return result.clip;
}

} // namespace osgActor
