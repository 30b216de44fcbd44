#include <osgActor/io/ActorDocument>

namespace osgActor {

namespace {

/** What every controller has: name, weight, on or off. */
void describeController(const Controller& controller, PlayerDocument& document)
{
    document.name = controller.getName();
    document.weight = controller.getWeight();
    document.enabled = controller.getEnabled();
}

void applyController(const PlayerDocument& document, Controller& controller)
{
    controller.setName(document.name);
    controller.setWeight(document.weight);
    controller.setEnabled(document.enabled);
}

/** What both kinds of player have besides: the play head, its mode and speed, playing or waiting. ClipPlayer and
  * TrajectoryPlayer name these alike but share no base for them. */
template <class Player>
void applyPlayHead(const PlayerDocument& document, Player& player)
{
    player.setPlayMode(document.playMode);
    if (document.playing) player.play();
    else player.pause();
    player.setSpeed(document.speed);
    if (document.time) player.seek(*document.time);
}

template <class Player>
void describePlayHead(const Player& player, bool started, PlayerDocument& document)
{
    document.playing = player.isPlaying();
    document.playMode = player.getPlayMode();
    if (started) document.time = player.getPlayTime();
    document.speed = player.getSpeed();
}

} // namespace

PlayerDocument describeClipPlayer(const ClipPlayer& player, const ActorDefinition& definition)
{
    PlayerDocument document;
    describeController(player, document);
    document.clip = player.getClip() ? player.getClip()->getName() : std::string();
    describePlayHead(player, player.getPlayTime() != 0.0, document); // a clip's play head starts at 0
    document.fade = player.getFadeWeight();
    document.rootMotion = player.getRootMotion();
    document.rootJoint = player.getRootJointName();
    document.swayWindow = player.getSwayWindow();
    const DofSelection& selection = player.getSelection();
    if (selection.drivesAll()) return document;
    for (unsigned dof = 0; dof < definition.getNumDofs(); ++dof)
        if (selection.weight(dof) > 0.0)
            document.dofWeights.emplace_back(definition.getDofName(dof), selection.weight(dof));
    // A selection that drives nothing is still not "every DOF": one DOF at weight 0 says so.
    if (document.dofWeights.empty() && definition.getNumDofs() > 0)
        document.dofWeights.emplace_back(definition.getDofName(0), 0.0);
    return document;
}

std::shared_ptr<ClipPlayer> makeClipPlayer(const PlayerDocument& document, ClipPtr clip,
                                           const ActorDefinition& definition)
{
    auto player = std::make_shared<ClipPlayer>(std::move(clip));
    applyController(document, *player);
    applyPlayHead(document, *player);
    player->setFadeWeight(document.fade);
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

PlayerDocument describeTrajectoryPlayer(const TrajectoryPlayer& player)
{
    PlayerDocument document;
    describeController(player, document);
    document.trajectory = player.getTrajectory() ? player.getTrajectory()->getName() : std::string();
    describePlayHead(player, player.hasStarted(), document);
    return document;
}

std::shared_ptr<TrajectoryPlayer> makeTrajectoryPlayer(const PlayerDocument& document, TrajectoryPtr trajectory)
{
    auto player = std::make_shared<TrajectoryPlayer>(std::move(trajectory));
    applyController(document, *player);
    applyPlayHead(document, *player);
    return player;
}

} // namespace osgActor
