#include <TestMath>

#include <osgActor/core/ActorDefinitionBuilder>
#include <osgActor/core/ClipBuilder>
#include <osgActor/core/ClipPlayer>

#include <gtest/gtest.h>

#include <glm/ext/matrix_transform.hpp>
#include <glm/ext/quaternion_trigonometric.hpp>
#include <glm/ext/scalar_constants.hpp>
#include <glm/gtc/quaternion.hpp>

#include <cmath>
#include <string>
#include <vector>

using namespace osgActor;
using namespace osgActor::test;

namespace {

const double kPi = glm::pi<double>();

/** hips: tx, ty, tz (before rotation) and rz (yaw about +Z); head 1 above the hips, rx. */
ActorDefinitionPtr makeWalker()
{
    ActorDefinitionBuilder b("walker");
    b.addJoint("hips").dofs(kTranslationDofs | Dof::RZ).translationMode(TranslationMode::BeforeRotation);
    b.addJoint("head", "hips").offset(0, 0, 1).dofs(dofBit(Dof::RX));
    return b.build().definition;
}

ClipPtr makeClip(std::initializer_list<std::pair<const char*, std::vector<std::pair<double, double>>>> channels)
{
    ClipBuilder b("clip");
    for (const auto& channel : channels)
    {
        const unsigned c = b.addChannel(channel.first);
        for (const auto& key : channel.second) b.addKey(c, key.first, key.second);
    }
    const ClipBuildResult result = b.build();
    EXPECT_TRUE(result) << result.error;
    return result.clip;
}

/** One actor instance driven by controllers, as ActorNode drives it. */
struct Rig
{
    explicit Rig(ActorDefinitionPtr definition) : pose(std::move(definition)) {}
    void run(const std::vector<ControllerPtr>& controllers, double deltaTime)
    {
        ControllerContext context;
        time += deltaTime;
        context.time = time;
        context.deltaTime = deltaTime;
        ControllerTarget target{pose, transforms};
        runControllers(controllers, context, target);
        pose.updateMatrices();
    }
    double dof(const std::string& name) const
    {
        return pose.getDof(static_cast<unsigned>(pose.getDefinition()->findDof(name)));
    }
    /** A joint in the actor's parent frame: pretr_m * posttr_m * model. */
    glm::dmat4 world(unsigned joint) const
    {
        auto placed = [](const glm::dvec3& t, const glm::dquat& q) {
            return glm::translate(glm::dmat4(1.0), t) * glm::mat4_cast(q);
        };
        return placed(transforms.preTranslation, transforms.preRotation) *
               placed(transforms.postTranslation, transforms.postRotation) * pose.getModelMatrix(joint);
    }
    ActorPose pose;
    ActorTransforms transforms;
    double time = 0.0;
};

} // namespace

TEST(ClipPlayer, DoesNothingWithoutAClipOrOnAnActorWithoutItsDofs)
{
    Rig rig(makeWalker());
    auto empty = std::make_shared<ClipPlayer>();
    rig.run({empty}, 0.1);
    EXPECT_EQ(rig.pose.getDofs(), rig.pose.getDefinition()->getDefaultDofs());
    auto foreign = std::make_shared<ClipPlayer>(makeClip({{"tail.rx", {{0, 1}, {1, 2}}}}));
    rig.run({foreign}, 0.1);
    EXPECT_EQ(rig.pose.getDofs(), rig.pose.getDefinition()->getDefaultDofs());
}

TEST(ClipPlayer, FoldsThePlayHeadByItsMode)
{
    auto player = std::make_shared<ClipPlayer>(makeClip({{"head.rx", {{0, 0}, {2, 2}}}}));
    player->seek(3.0);
    EXPECT_DOUBLE_EQ(player->getClipTime(), 1.0); // Loop, the default
    player->setPlayMode(PlayMode::PingPong);
    EXPECT_DOUBLE_EQ(player->getClipTime(), 1.0);
    player->seek(2.5);
    EXPECT_DOUBLE_EQ(player->getClipTime(), 2.0 - 0.5) << "on the way back";
    player->seek(4.5);
    EXPECT_DOUBLE_EQ(player->getClipTime(), 0.5) << "forwards again";
    player->setPlayMode(PlayMode::Once);
    EXPECT_DOUBLE_EQ(player->getClipTime(), 2.0);
    EXPECT_TRUE(player->isFinished());
    player->seek(-1.0);
    player->setPlayMode(PlayMode::Loop);
    EXPECT_DOUBLE_EQ(player->getClipTime(), 1.0);
}

TEST(ClipPlayer, AdvancesWithTheFrameTimeSpeedAndPause)
{
    Rig rig(makeWalker());
    // head.rx = t / 2 radians over 4 seconds.
    auto player = std::make_shared<ClipPlayer>(makeClip({{"head.rx", {{0, 0}, {4, 2}}}}));
    rig.run({player}, 0.0);
    EXPECT_DOUBLE_EQ(rig.dof("head.rx"), 0.0);
    rig.run({player}, 0.5);
    EXPECT_DOUBLE_EQ(rig.dof("head.rx"), 0.25);
    player->setSpeed(2.0);
    rig.run({player}, 0.5);
    EXPECT_DOUBLE_EQ(rig.dof("head.rx"), 0.75);
    player->pause();
    rig.run({player}, 0.5);
    EXPECT_DOUBLE_EQ(rig.dof("head.rx"), 0.75);
    player->play();
    player->setSpeed(-1.0);
    rig.run({player}, 0.25);
    EXPECT_DOUBLE_EQ(rig.dof("head.rx"), 0.625);
    player->seek(3.0);
    rig.run({player}, 0.0);
    EXPECT_DOUBLE_EQ(rig.dof("head.rx"), 1.5);
}

TEST(ClipPlayer, DrivesOnlyItsSelection)
{
    Rig rig(makeWalker());
    auto player = std::make_shared<ClipPlayer>(makeClip({{"head.rx", {{0, 1}}}, {"hips.rz", {{0, 1}}}}));
    player->setSelection(DofSelection::joints(*rig.pose.getDefinition(), {"head"}, false));
    rig.run({player}, 0.1);
    EXPECT_DOUBLE_EQ(rig.dof("head.rx"), 1.0);
    EXPECT_DOUBLE_EQ(rig.dof("hips.rz"), 0.0);
}

TEST(ClipPlayer, CrossFadesBetweenClips)
{
    Rig rig(makeWalker());
    auto from = std::make_shared<ClipPlayer>(makeClip({{"head.rx", {{0, 0.2}}}}));
    auto to = std::make_shared<ClipPlayer>(makeClip({{"head.rx", {{0, 1.0}}}}));
    to->setFadeWeight(0.0);
    rig.run({from, to}, 0.0);
    EXPECT_DOUBLE_EQ(rig.dof("head.rx"), 0.2);
    crossFade(*from, *to, 1.0);
    rig.run({from, to}, 0.25);
    // from writes 0.2 whole; to (fade 0.25) blends a quarter of the way to 1.
    EXPECT_NEAR(rig.dof("head.rx"), 0.2 + 0.25 * 0.8, 1e-12);
    rig.run({from, to}, 0.25);
    EXPECT_NEAR(rig.dof("head.rx"), 0.2 + 0.5 * (1.0 - 0.2), 1e-12);
    EXPECT_DOUBLE_EQ(from->getFadeWeight(), 1.0);
    rig.run({from, to}, 1.0);
    EXPECT_DOUBLE_EQ(from->getFadeWeight(), 0.0) << "stopped once the new clip is whole";
    EXPECT_DOUBLE_EQ(rig.dof("head.rx"), 1.0);
}

TEST(ClipPlayer, SplitsRootTravelIntoPreAndPostTransformsWithoutMovingTheActor)
{
    // Walks 2 along X while bobbing 1 -> 1.2 -> 1 in Z and turning a quarter turn.
    const ClipPtr walk = makeClip({{"hips.tx", {{0, 0}, {1, 2}}},
                                   {"hips.tz", {{0, 1}, {0.5, 1.2}, {1, 1}}},
                                   {"hips.rz", {{0, 0}, {1, kPi / 2}}}});
    Rig stored(makeWalker()), split(makeWalker());
    auto storedPlayer = std::make_shared<ClipPlayer>(walk);
    auto splitPlayer = std::make_shared<ClipPlayer>(walk);
    splitPlayer->setRootMotion(RootMotion::ToTransforms);
    split.transforms.preTranslation = glm::dvec3(10, 0, 0); // where the user put the actor
    stored.transforms.preTranslation = glm::dvec3(10, 0, 0);
    for (double dt : {0.0, 0.25, 0.5})
    {
        stored.run({storedPlayer}, dt);
        split.run({splitPlayer}, dt);
        SCOPED_TRACE("time " + std::to_string(split.time));
        for (unsigned j = 0; j < 2; ++j) EXPECT_TRUE(matricesNear(split.world(j), stored.world(j), 1e-12)) << j;
        EXPECT_DOUBLE_EQ(split.dof("hips.tx"), 0.0) << "the travel left the skeleton";
        EXPECT_DOUBLE_EQ(split.transforms.preTranslation.z, 0.0) << "the path is on the ground";
        EXPECT_NEAR(split.transforms.preTranslation.x, 10.0 + 2.0 * split.time, 1e-12);
        EXPECT_NEAR(split.transforms.postTranslation.z, stored.dof("hips.tz"), 1e-12) << "the bob";
        // The reference point's heading follows the root's yaw.
        EXPECT_NEAR(glm::angle(split.transforms.preRotation), kPi / 2 * split.time, 1e-9);
    }
}

TEST(ClipPlayer, CarriesTheRootPathOnAcrossLoops)
{
    auto player = std::make_shared<ClipPlayer>(makeClip({{"hips.tx", {{0, 0}, {1, 1}}}}));
    player->setRootMotion(RootMotion::ToTransforms);
    Rig rig(makeWalker());
    rig.run({player}, 0.0);
    for (int i = 0; i < 5; ++i) rig.run({player}, 0.5);
    EXPECT_NEAR(rig.transforms.preTranslation.x, 2.5, 1e-12);
    EXPECT_TRUE(vectorsNear(glm::dvec3(rig.world(0)[3]), glm::dvec3(2.5, 0, 0), 1e-12));
}

TEST(ClipPlayer, PlaysInPlace)
{
    auto player =
        std::make_shared<ClipPlayer>(makeClip({{"hips.tx", {{0, 0}, {1, 2}}}, {"hips.tz", {{0, 1}, {1, 1.5}}}}));
    player->setRootMotion(RootMotion::InPlace);
    Rig rig(makeWalker());
    rig.transforms.preTranslation = glm::dvec3(5, 0, 0);
    rig.run({player}, 0.0);
    rig.run({player}, 0.5);
    EXPECT_TRUE(vectorsNear(rig.transforms.preTranslation, glm::dvec3(5, 0, 0)));
    EXPECT_TRUE(vectorsNear(glm::dvec3(rig.world(0)[3]), glm::dvec3(5, 0, 1.25), 1e-12));
}

TEST(ClipPlayer, PutsTheSwayInThePostTransformWhenAsked)
{
    // Walks 4 along X in 4 s, swaying 0.1 to either side every second.
    const ClipPtr walk = makeClip({{"hips.tx", {{0, 0}, {4, 4}}},
                                   {"hips.ty", {{0, 0}, {0.5, 0.1}, {1, 0}, {1.5, -0.1}, {2, 0}, {2.5, 0.1}, {3, 0},
                                                {3.5, -0.1}, {4, 0}}}});
    Rig stored(makeWalker()), split(makeWalker());
    auto storedPlayer = std::make_shared<ClipPlayer>(walk);
    auto splitPlayer = std::make_shared<ClipPlayer>(walk);
    splitPlayer->setRootMotion(RootMotion::ToTransforms);
    splitPlayer->setSwayWindow(1.0);
    stored.run({storedPlayer}, 0.0);
    split.run({splitPlayer}, 0.0);
    for (int step = 0; step < 3; ++step)
    {
        stored.run({storedPlayer}, 0.5);
        split.run({splitPlayer}, 0.5);
        SCOPED_TRACE("time " + std::to_string(split.time));
        for (unsigned j = 0; j < 2; ++j) EXPECT_TRUE(matricesNear(split.world(j), stored.world(j), 1e-12)) << j;
    }
    // At 1.5 s the hips are at (1.5, -0.1): the path (midpoint of 1 s and 2 s) is (1.5, 0), the sway -0.1.
    EXPECT_TRUE(vectorsNear(split.transforms.preTranslation, glm::dvec3(1.5, 0, 0), 1e-12));
    EXPECT_TRUE(vectorsNear(split.transforms.postTranslation, glm::dvec3(0, -0.1, 0), 1e-12));
}

TEST(ClipPlayer, WritesRunsOfChannelsAsItWritesThemOneByOne)
{
    // A clip made for the skeleton (channels in DOF order: one run, sampled and written in bulk) and the same
    // motion with its channels reversed (no run: channel by channel) must pose two actors alike, clamps, a wrap
    // through 180 degrees and a selection that splits the run included. 50 joints: the whole run (150 DOFs) is
    // longer than the player's sampling chunk.
    ActorDefinitionBuilder b("chain");
    b.addJoint("j0").dofs(kRotationDofs).limits(Dof::RY, -0.5, 0.5);
    for (unsigned j = 1; j < 50; ++j)
        b.addJoint("j" + std::to_string(j), "j" + std::to_string(j - 1)).offset(0, 0, 0.2).dofs(kRotationDofs);
    const ActorDefinitionPtr definition = b.build().definition;
    const unsigned numDofs = definition->getNumDofs();
    const unsigned numFrames = 8;
    std::vector<double> frames(numFrames * numDofs);
    for (unsigned f = 0; f < numFrames; ++f)
        for (unsigned d = 0; d < numDofs; ++d) frames[f * numDofs + d] = std::sin(0.7 * f + 1.3 * d) * 2.0;
    frames[3 * numDofs + 7] = 3.0; // a wrap from about 172 to about -172 degrees between frames 3 and 4
    frames[4 * numDofs + 7] = -3.0;
    ClipBuilder inOrder("inOrder"), reversed("reversed");
    for (unsigned d = 0; d < numDofs; ++d) inOrder.addChannel(definition->getDofName(d));
    for (unsigned d = numDofs; d-- > 0;) reversed.addChannel(definition->getDofName(d));
    std::vector<double> reversedFrames(frames.size());
    for (unsigned f = 0; f < numFrames; ++f)
        for (unsigned d = 0; d < numDofs; ++d)
            reversedFrames[f * numDofs + (numDofs - 1 - d)] = frames[f * numDofs + d];
    inOrder.setFrames(30.0, frames);
    reversed.setFrames(30.0, reversedFrames);

    for (bool splitRun : {false, true})
    {
        Rig bulk(definition), oneByOne(definition);
        auto bulkPlayer = std::make_shared<ClipPlayer>(inOrder.build().clip);
        auto onePlayer = std::make_shared<ClipPlayer>(reversed.build().clip);
        for (const auto& player : {bulkPlayer, onePlayer})
        {
            player->setPlayMode(PlayMode::Loop);
            player->play();
            if (splitRun) // every joint but j5 and j6: two runs
                player->setSelection(DofSelection::joints(
                    *definition, {"j0", "j1", "j2", "j3", "j4", "j7", "j8", "j9", "j10", "j11"}, false));
        }
        for (int frame = 0; frame < 20; ++frame)
        {
            bulk.run({bulkPlayer}, 1.0 / 45.0); // between the clip's frames as often as on them
            oneByOne.run({onePlayer}, 1.0 / 45.0);
            ASSERT_EQ(bulk.pose.getDofs(), oneByOne.pose.getDofs()) << "frame " << frame;
        }
        EXPECT_LE(bulk.dof("j0.ry"), 0.5) << "clamped to its limit";
        EXPECT_EQ(bulk.dof("j6.rx") == 0.0, splitRun) << "driven only inside the selection";
    }
}
