#include <osgActor/io/ActorDocument>

namespace osgActor {

PlayerDocument describeClipPlayer(const ClipPlayer& player, const ActorDefinition& definition)
{
    PlayerDocument document;
    document.name = player.getName();
    document.clip = player.getClip() ? player.getClip()->getName() : std::string();
    document.playing = player.isPlaying();
    document.playMode = player.getPlayMode();
    document.time = player.getPlayTime();
    document.speed = player.getSpeed();
    document.weight = player.getWeight();
    document.fade = player.getFadeWeight();
    document.enabled = player.getEnabled();
    document.rootMotion = player.getRootMotion();
    document.rootJoint = player.getRootJointName();
    document.swayWindow = player.getSwayWindow();
    const DofSelection& selection = player.getSelection();
    if (selection.drivesAll()) return document;
    for (unsigned dof = 0; dof < definition.getNumDofs(); ++dof)
        if (selection.weight(dof) > 0.0) document.dofWeights.emplace_back(definition.getDofName(dof), selection.weight(dof));
    // A selection that drives nothing is still not "every DOF": one DOF at weight 0 says so.
    if (document.dofWeights.empty() && definition.getNumDofs() > 0)
        document.dofWeights.emplace_back(definition.getDofName(0), 0.0);
    return document;
}

std::shared_ptr<ClipPlayer> makeClipPlayer(const PlayerDocument& document, ClipPtr clip,
                                           const ActorDefinition& definition)
{
    auto player = std::make_shared<ClipPlayer>(std::move(clip));
    player->setName(document.name);
    player->setPlayMode(document.playMode);
    if (document.playing) player->play();
    else player->pause();
    player->setSpeed(document.speed);
    player->seek(document.time);
    player->setWeight(document.weight);
    player->setFadeWeight(document.fade);
    player->setEnabled(document.enabled);
    player->setRootMotion(document.rootMotion, document.rootJoint);
    player->setSwayWindow(document.swayWindow);
    if (!document.dofWeights.empty())
    {
        DofSelection selection;
        for (const auto& dofWeight : document.dofWeights)
        {
            const int dof = definition.findDof(dofWeight.first);
            if (dof >= 0) selection.setWeight(definition.getNumDofs(), static_cast<unsigned>(dof), dofWeight.second);
        }
        player->setSelection(selection);
    }
    return player;
}

} // namespace osgActor
