/* Clip players through every format osgDB writes actors to (.actor, and .osgt/.osgb/.osgx/.osg, which carry the
 * actor's definition document): each comes back under its name, in its place among the actor's controllers, with
 * its state, and plays on exactly as the original does. */
#include "PluginTestUtil"

#include "../nodes/NodeTestUtil"

#include <osgActor/ActorSceneIO>
#include <osgActor/core/ClipBuilder>
#include <osgActor/core/ClipLibrary>
#include <osgActor/core/ClipPlayer>
#include <osgActor/core/Trajectory>

#include <osgDB/WriteFile>

#include <cmath>

using namespace osgActor;
using namespace osgActor::test;

namespace {

const double kDegree = std::acos(-1.0) / 180.0;

std::shared_ptr<ClipPlayer> addPlayer(ActorNode& actor, const std::string& name, ClipPtr clip)
{
    auto player = std::make_shared<ClipPlayer>(std::move(clip));
    player->setName(name);
    actor.addController(player);
    return player;
}

/** The humanoid with four players of state a file must keep, none of it a new player's: one of a clip in the
  * actor's library, one of the same clip on the right arm only, one of a path, and one of a clip the library does
  * not hold. */
osg::ref_ptr<ActorNode> makeActorWithPlayers()
{
    osg::ref_ptr<ActorNode> actor = readActorFile(dataFile("humanoid.actor"));
    if (!actor || !actor->getClipLibrary()) return nullptr;
    const ClipPtr wave = actor->getClipLibrary()->getClip("wave");

    auto base = addPlayer(*actor, "base wave", wave);
    base->setPlayMode(PlayMode::PingPong);
    base->setSpeed(0.5);
    base->seek(0.25);

    auto arm = addPlayer(*actor, "right arm", wave);
    arm->setPlayMode(PlayMode::Once);
    arm->seek(1.125);
    arm->pause();
    arm->setWeight(0.5);
    arm->setFadeWeight(0.75);
    DofSelection selection = DofSelection::joints(*actor->getDefinition(), {"r_shoulder"}, true);
    selection.setWeight(actor->getNumDofs(), static_cast<unsigned>(actor->getDefinition()->findDof("r_elbow.rx")),
                        0.375);
    arm->setSelection(selection);
    arm->setSwayWindow(0.2);

    // Between the clip players, a path's player, started and half-way along.
    const TrajectoryBuildResult stroll = TrajectoryBuilder::build(
        "stroll", {TrajectoryKey{0.0, glm::dvec3(0.0), 0.0}, TrajectoryKey{4.0, glm::dvec3(2.0, 1.0, 0.0), 0.5}});
    if (!stroll) return nullptr;
    auto path = std::make_shared<TrajectoryPlayer>(stroll.trajectory);
    path->setName("strolling");
    path->setPlayMode(PlayMode::PingPong);
    path->seek(2.0);
    path->setSpeed(0.75);
    actor->addController(path);

    ClipBuilder nodBuilder("nod");
    const unsigned neck = nodBuilder.addChannel("skullbase.rx", Interpolation::Cubic);
    nodBuilder.addKey(neck, 0.0, 0.0);
    nodBuilder.addKey(neck, 0.5, 20.0 * kDegree);
    nodBuilder.addKey(neck, 1.0, 0.0);
    auto nod = addPlayer(*actor, "nod", nodBuilder.build().clip);
    nod->setRootMotion(RootMotion::InPlace, "HumanoidRoot");
    nod->setEnabled(false);
    return actor;
}

class PlayerRoundTrip : public ::testing::TestWithParam<const char*>
{
};

} // namespace

TEST_P(PlayerRoundTrip, PlayersComeBackWithTheirNamesOrderAndStateAndPlayOnTheSame)
{
    const std::string extension = GetParam();
    osg::ref_ptr<ActorNode> actor = makeActorWithPlayers();
    ASSERT_TRUE(actor.valid());
    const std::string path = outFile("players." + extension);
    ASSERT_TRUE(osgDB::writeNodeFile(*actor, path)) << path;
    osg::ref_ptr<ActorNode> back = readActorFile(path);
    ASSERT_TRUE(back.valid()) << extension;

    ASSERT_EQ(back->getControllers().size(), actor->getControllers().size()) << extension;
    for (std::size_t i = 0; i < actor->getControllers().size(); ++i)
    {
        if (const auto path = std::dynamic_pointer_cast<TrajectoryPlayer>(actor->getControllers()[i]))
        {
            const auto read = std::dynamic_pointer_cast<TrajectoryPlayer>(back->getControllers()[i]);
            ASSERT_TRUE(read) << extension << " controller " << i;
            EXPECT_EQ(read->getName(), path->getName()) << extension;
            ASSERT_TRUE(read->getTrajectory()) << extension;
            EXPECT_EQ(read->getTrajectory()->getName(), path->getTrajectory()->getName()) << extension;
            EXPECT_EQ(read->isPlaying(), path->isPlaying()) << extension;
            EXPECT_EQ(read->getPlayMode(), path->getPlayMode()) << extension;
            EXPECT_EQ(read->hasStarted(), path->hasStarted()) << extension;
            EXPECT_EQ(read->getPlayTime(), path->getPlayTime()) << extension;
            EXPECT_EQ(read->getSpeed(), path->getSpeed()) << extension;
            continue;
        }
        const auto original = std::dynamic_pointer_cast<ClipPlayer>(actor->getControllers()[i]);
        const auto read = std::dynamic_pointer_cast<ClipPlayer>(back->getControllers()[i]);
        ASSERT_TRUE(original && read) << extension << " controller " << i;
        const std::string which = extension + " " + original->getName();
        EXPECT_EQ(read->getName(), original->getName()) << extension << " controller " << i;
        ASSERT_TRUE(read->getClip()) << which;
        EXPECT_EQ(read->getClip()->getName(), original->getClip()->getName()) << which;
        EXPECT_EQ(read->isPlaying(), original->isPlaying()) << which;
        EXPECT_EQ(read->getPlayMode(), original->getPlayMode()) << which;
        EXPECT_EQ(read->getPlayTime(), original->getPlayTime()) << which;
        EXPECT_EQ(read->getSpeed(), original->getSpeed()) << which;
        EXPECT_EQ(read->getWeight(), original->getWeight()) << which;
        EXPECT_EQ(read->getFadeWeight(), original->getFadeWeight()) << which;
        EXPECT_EQ(read->getEnabled(), original->getEnabled()) << which;
        EXPECT_EQ(read->getRootMotion(), original->getRootMotion()) << which;
        EXPECT_EQ(read->getRootJointName(), original->getRootJointName()) << which;
        EXPECT_EQ(read->getSwayWindow(), original->getSwayWindow()) << which;
        EXPECT_EQ(read->getSelection().weights(), original->getSelection().weights()) << which;
    }
    ASSERT_TRUE(back->getClipLibrary()) << extension;
    EXPECT_TRUE(back->getClipLibrary()->getClip("nod")) << extension << ": the clip only a player held came too";

    // Played on side by side, both give the same pose: the base wave at half speed, the arm's weights over it.
    std::dynamic_pointer_cast<ClipPlayer>(actor->findController("right arm"))->play();
    std::dynamic_pointer_cast<ClipPlayer>(back->findController("right arm"))->play();
    for (unsigned frame : {1u, 20u, 45u})
    {
        runUpdate(*actor, frame);
        runUpdate(*back, frame);
    }
    EXPECT_TRUE(vec3Near(back->getPreTranslation(), actor->getPreTranslation(), 1e-12)) << extension;
    EXPECT_GT(actor->getPreTranslation().length(), 0.1) << "the path moved the actor";
    for (unsigned dof = 0; dof < actor->getNumDofs(); ++dof)
        EXPECT_NEAR(back->getDof(dof), actor->getDof(dof), 1e-12)
            << extension << " " << actor->getDefinition()->getDofName(dof);
    double elbow = 0.0;
    ASSERT_TRUE(actor->getDof("r_elbow.rx", elbow));
    EXPECT_LT(elbow, -1e-3) << "the players moved the arm, so the comparison means something";
}

INSTANTIATE_TEST_SUITE_P(EveryFormat, PlayerRoundTrip, ::testing::Values("actor", "osgt", "osgb", "osgx", "osg"),
                         [](const ::testing::TestParamInfo<const char*>& info) { return std::string(info.param); });

TEST(PlayerRoundTrip, APlayerOfAnotherClipOrPathNamedLikeOneWrittenIsLeftOut)
{
    // A file names each clip and path once: a player of a second one of the same name would read back playing the
    // first, so the writer leaves it out (with a warning) rather than change what it plays.
    osg::ref_ptr<ActorNode> actor = readActorFile(dataFile("humanoid.actor"));
    ASSERT_TRUE(actor.valid());
    ClipBuilder other("wave");
    other.addKey(other.addChannel("skullbase.rx"), 0.0, 0.5);
    addPlayer(*actor, "library wave", actor->getClipLibrary()->getClip("wave"));
    addPlayer(*actor, "other wave", other.build().clip);
    const TrajectoryBuildResult first = TrajectoryBuilder::build("path", {TrajectoryKey{0.0, glm::dvec3(0.0), 0.0}});
    const TrajectoryBuildResult second = TrajectoryBuilder::build("path", {TrajectoryKey{0.0, glm::dvec3(1.0), 0.0}});
    ASSERT_TRUE(first && second);
    actor->addController(std::make_shared<TrajectoryPlayer>(first.trajectory));
    actor->addController(std::make_shared<TrajectoryPlayer>(second.trajectory));

    const ActorDocument document = extractActorDocument(*actor);
    ASSERT_EQ(document.players.size(), 2u);
    EXPECT_EQ(document.players[0].name, "library wave");
    EXPECT_TRUE(document.players[1].playsTrajectory());
    ASSERT_EQ(document.clips.size(), 1u);
    EXPECT_EQ(document.clips[0].clip, actor->getClipLibrary()->getClip("wave"));
    ASSERT_EQ(document.trajectories.size(), 1u);
    EXPECT_EQ(document.trajectories[0].trajectory, first.trajectory);
}
