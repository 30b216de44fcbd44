#include "ClipControls.h"

#include <osgActor/core/ClipLibrary>

#include <algorithm>
#include <cstdio>

namespace osgActorViewer {

std::shared_ptr<osgActor::ClipPlayer> findClipPlayer(const osgActor::ActorNode& actor)
{
    for (const osgActor::ControllerPtr& controller : actor.getControllers())
        if (auto player = std::dynamic_pointer_cast<osgActor::ClipPlayer>(controller)) return player;
    return nullptr;
}

std::string switchClip(osgActor::ActorNode& actor, int step)
{
    const osgActor::ClipLibraryPtr& library = actor.getClipLibrary();
    if (!library || library->getNumClips() == 0) return "this actor has no clips";
    const std::vector<std::string> names = library->getClipNames();

    std::shared_ptr<osgActor::ClipPlayer> player = findClipPlayer(actor);
    if (!player)
    {
        player = std::make_shared<osgActor::ClipPlayer>();
        player->setName("viewer");
        actor.addController(player);
    }
    // The clip after (or before) the one playing; the first one when none of the library's is playing.
    int current = -1;
    if (player->getClip())
    {
        const auto found = std::find(names.begin(), names.end(), player->getClip()->getName());
        if (found != names.end()) current = int(found - names.begin());
    }
    const int count = int(names.size());
    const int next = current < 0 ? 0 : ((current + step) % count + count) % count;
    player->setClip(library->getClip(names[next]));
    player->seek(0.0);
    player->play();
    return "playing clip " + names[next] + " (" + std::to_string(next + 1) + "/" + std::to_string(count) + ")";
}

std::string describeClip(const osgActor::ActorNode& actor)
{
    const std::shared_ptr<osgActor::ClipPlayer> player = findClipPlayer(actor);
    if (!player || !player->getClip()) return "none";
    char text[160];
    std::snprintf(text, sizeof(text), "%s  %.2f / %.2f s%s", player->getClip()->getName().c_str(),
                  player->getClipTime(), player->getClip()->getDuration(), player->isPlaying() ? "" : "  (stopped)");
    return text;
}

} // namespace osgActorViewer
