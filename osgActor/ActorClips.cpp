#include <osgActor/ActorClips>
#include <osgActor/io/ClipSection>

namespace osgActor {

bool addClipSections(ActorNode& actor, const std::vector<SyntaxStatement>& sections, const std::string& fileName,
                     std::string& error)
{
    std::vector<ClipPtr> clips;
    std::vector<ControllerPtr> players;
    for (const SyntaxStatement& section : sections)
    {
        if (section.keyword != "clip") continue;
        const ClipBuildResult read = clipFromSection(section, fileName);
        if (!read)
        {
            error = read.error;
            return false;
        }
        clips.push_back(read.clip);
        PlayMode mode;
        if (clipSectionPlays(section, mode))
        {
            auto player = std::make_shared<ClipPlayer>(read.clip);
            player->setName(read.clip->getName());
            player->setPlayMode(mode);
            players.push_back(player);
        }
    }
    if (clips.empty()) return true;
    if (!actor.getClipLibrary()) actor.setClipLibrary(std::make_shared<ClipLibrary>());
    for (const ClipPtr& clip : clips) actor.getClipLibrary()->addClip(clip);
    for (const ControllerPtr& player : players) actor.addController(player);
    return true;
}

} // namespace osgActor
