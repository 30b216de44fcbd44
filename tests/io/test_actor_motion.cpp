/* readActorMotion(): an actor's clips, trajectories, players and IK chains read on their own, for a definition and a
 * clip library read before (what OSG's formats store per actor). */
#include "ActorTextTestUtil"

#include <osgActor/core/ClipBuilder>

#include <cmath>

using namespace osgActor;
using namespace osgActor::test;

namespace {

/** A two-joint arm: shoulder (rx, ry), elbow 0.3 below it (rx). */
ActorDefinitionPtr makeArm()
{
    const ActorReadResult arm = read("osgactor 1\nactor arm {\n joint shoulder {\n  dof rx; dof ry\n"
                                     "  joint elbow { offset 0 0 -0.3; dof rx }\n }\n}\n");
    EXPECT_TRUE(arm) << arm.error;
    return arm.definition;
}

ClipPtr makeClip(const std::string& name)
{
    ClipBuilder builder(name);
    const unsigned channel = builder.addChannel("elbow.rx", Interpolation::Linear);
    builder.addKey(channel, 0.0, 0.0);
    builder.addKey(channel, 1.0, -1.0);
    return builder.build().clip;
}

ActorReadResult readMotion(const std::string& text, const ActorDefinitionPtr& definition,
                           const std::vector<ClipPtr>& known = {})
{
    std::istringstream in(text);
    return readActorMotion(in, "motion", definition, known);
}

std::string motionError(const std::string& text, const ActorDefinitionPtr& definition,
                        const std::vector<ClipPtr>& known = {})
{
    const ActorReadResult result = readMotion(text, definition, known);
    EXPECT_FALSE(result) << text;
    EXPECT_TRUE(result.document.players.empty());
    EXPECT_TRUE(result.ikChains.empty());
    return result.error;
}

} // namespace

TEST(ActorMotion, WithoutADefinitionNothingIsRead)
{
    EXPECT_EQ(motionError("player p { clip wave }\n", nullptr), "motion: an actor's motion needs the actor's definition");
}

TEST(ActorMotion, AnythingButMotionSectionsIsRefusedAtItsLine)
{
    const ActorDefinitionPtr arm = makeArm();
    EXPECT_EQ(motionError("trajectory t { key 0 0 0 0 0 }\njoint extra { dof rz }\n", arm),
              "motion:2: unknown keyword 'joint' in an actor's motion");
    EXPECT_EQ(motionError("pre_translation 1 2 3\n", arm),
              "motion:1: unknown keyword 'pre_translation' in an actor's motion");
}

TEST(ActorMotion, APlayerOfAClipNeitherTheLibraryNorTheTextHoldsIsRefused)
{
    EXPECT_EQ(motionError("player p {\n clip wave\n}\n", makeArm()),
              "motion:1: player 'p' plays clip 'wave', which the actor does not have");
}

TEST(ActorMotion, AClipOfTheTextMayNotTakeTheNameOfOneInTheLibrary)
{
    EXPECT_EQ(motionError("\nclip wave { channel elbow.rx { key 0 0 } }\n", makeArm(), {makeClip("wave")}),
              "motion:2: clip 'wave' is in the actor's clip library already");
}

TEST(ActorMotion, ClipsAreCheckedAgainstTheDefinition)
{
    EXPECT_EQ(motionError("clip c {\n channel knee.rx { key 0 0 }\n}\n", makeArm()),
              "motion:2: channel 'knee.rx' names no DOF of the actor");
}

TEST(ActorMotion, PlayersOfTheLibrarysClipsAndTheTextsTrajectoriesAndChainsAreRead)
{
    const ActorDefinitionPtr arm = makeArm();
    const ClipPtr wave = makeClip("wave");
    const ActorReadResult result = readMotion("clip nod { channel shoulder.rx { key 0 0; key 1 90 } }\n"
                                              "trajectory path { key 0 0 0 0 0; key 2 1 0 0 90 }\n"
                                              "player waving { clip wave; play once; time 0.5 }\n"
                                              "player nodding { clip nod }\n"
                                              "player walking { trajectory path }\n"
                                              "ikchain reach { root shoulder; effector elbow }\n",
                                              arm, {wave});
    ASSERT_TRUE(result) << result.error;
    EXPECT_EQ(result.definition, arm) << "the definition given, not a new one";
    ASSERT_EQ(result.document.clips.size(), 2u);
    EXPECT_EQ(result.document.clips[0].clip, wave) << "the library's clip itself, first";
    ASSERT_TRUE(result.document.clips[1].clip);
    EXPECT_EQ(result.document.clips[1].clip->getName(), "nod");
    // The text's angles are degrees, as in a whole file: 90 degrees is a quarter turn.
    EXPECT_DOUBLE_EQ(result.document.clips[1].clip->getKeyValue(0, 1), std::acos(-1.0) / 2.0);
    ASSERT_EQ(result.document.trajectories.size(), 1u);
    EXPECT_EQ(result.document.trajectories[0].name(), "path");
    ASSERT_EQ(result.document.players.size(), 3u);
    EXPECT_EQ(result.document.players[0].clip, "wave");
    EXPECT_EQ(result.document.players[0].playMode, PlayMode::Once);
    ASSERT_TRUE(result.document.players[0].time);
    EXPECT_EQ(*result.document.players[0].time, 0.5);
    EXPECT_EQ(result.document.players[2].trajectory, "path");
    ASSERT_EQ(result.ikChains.size(), 1u);
    EXPECT_EQ(result.ikChains[0]->getName(), "reach");
}
