/* The "player" section of .actor files: a player's name and state, read, refused and written back. */
#include "ActorTextTestUtil"

#include <optional>

using namespace osgActor;
using namespace osgActor::test;

namespace {

// Lines 1-11: an arm with two joints and a clip; a test's player starts at line 12.
const std::string kArm = "osgactor 1\nactor arm {\n joint shoulder {\n  dof rz\n  dof ry\n"
                         "  joint elbow { offset 1 0 0; dof rx }\n }\n clip wave {\n  channel shoulder.rz {\n"
                         "   key 0 0; key 1 90\n  } }\n";

} // namespace

TEST(ActorPlayers, AreReadWithTheirStateInFileOrder)
{
    const ActorReadResult result =
        read(kArm + " player \"upper wave\" {\n  clip wave\n  play pingpong\n  time 0.75\n  speed -2\n  weight 0.5\n"
                    "  fade 0.25\n  disabled\n  root_motion in_place shoulder\n  sway_window 0.4\n"
                    "  dof shoulder.rz 1\n  dof elbow.rx 0.125\n }\n"
                    " player waiting {\n  clip wave\n  play once\n  paused\n }\n player plain { clip wave }\n}\n");
    ASSERT_TRUE(result) << result.error;
    ASSERT_EQ(result.document.players.size(), 3u);
    const PlayerDocument& full = result.document.players[0];
    EXPECT_EQ(full.name, "upper wave");
    EXPECT_EQ(full.clip, "wave");
    EXPECT_EQ(full.line, 12);
    EXPECT_TRUE(full.playing);
    EXPECT_EQ(full.playMode, PlayMode::PingPong);
    EXPECT_EQ(full.time, std::optional<double>(0.75));
    EXPECT_EQ(full.speed, -2.0);
    EXPECT_EQ(full.weight, 0.5);
    EXPECT_EQ(full.fade, 0.25);
    EXPECT_FALSE(full.enabled);
    EXPECT_EQ(full.rootMotion, RootMotion::InPlace);
    EXPECT_EQ(full.rootJoint, "shoulder");
    EXPECT_EQ(full.swayWindow, 0.4);
    const std::vector<std::pair<std::string, double>> weights{{"shoulder.rz", 1.0}, {"elbow.rx", 0.125}};
    EXPECT_EQ(full.dofWeights, weights);
    const PlayerDocument& waiting = result.document.players[1];
    EXPECT_FALSE(waiting.playing) << "paused: the player waits, in its mode";
    EXPECT_EQ(waiting.playMode, PlayMode::Once);
    const PlayerDocument& plain = result.document.players[2];
    EXPECT_FALSE(plain.playing) << "without 'play' a player waits";
    EXPECT_EQ(plain.playMode, PlayMode::Loop) << "a new ClipPlayer's mode";
    EXPECT_TRUE(plain.enabled);
    EXPECT_TRUE(plain.dofWeights.empty()) << "every DOF at weight 1";
    EXPECT_FALSE(plain.time.has_value()) << "a new player's play head";
}

TEST(ActorPlayers, AreWrittenWithWhatDiffersFromANewPlayerAndReadBackTheSame)
{
    const ActorReadResult result =
        read(kArm + " player \"upper wave\" {\n  clip wave\n  play pingpong\n  time 0.75\n  speed -2\n  weight 0.5\n"
                    "  fade 0.25\n  disabled\n  root_motion to_transforms\n  sway_window 0.4\n"
                    "  dof shoulder.rz 1\n  dof elbow.rx 0.125\n }\n"
                    " player looping {\n  clip wave\n  play loop\n }\n player waiting {\n  clip wave\n }\n}\n");
    ASSERT_TRUE(result) << result.error;
    const std::string text = written(result.document);
    EXPECT_NE(text.find("    player \"upper wave\" {\n        clip wave\n        play pingpong\n        time 0.75\n"
                        "        speed -2\n        weight 0.5\n        disabled\n        fade 0.25\n"
                        "        root_motion to_transforms\n        sway_window 0.4\n        dof shoulder.rz 1\n"
                        "        dof elbow.rx 0.125\n    }\n"
                        "    player looping {\n        clip wave\n        play loop\n    }\n"
                        "    player waiting {\n        clip wave\n        paused\n    }\n}\n"),
              std::string::npos)
        << text;
    expectRewrittenTheSame(text);
}

TEST(ActorPlayers, BrokenOnesAreRefusedAtTheirLine)
{
    auto player = [](const std::string& body) { return kArm + " player p {\n" + body + " }\n}\n"; };
    EXPECT_EQ(readError(player("  play loop\n")),
              "t.actor:12: player 'p' needs either the 'clip' or the 'trajectory' it plays");
    EXPECT_EQ(readError(kArm + " trajectory t { key 0 0 0 0 0 }\n player p {\n  clip wave\n  trajectory t\n }\n}\n"),
              "t.actor:13: player 'p' needs either the 'clip' or the 'trajectory' it plays");
    EXPECT_EQ(readError(kArm + " player p {\n  trajectory t\n }\n}\n"),
              "t.actor:12: player 'p' plays trajectory 't', which the actor does not have");
    EXPECT_EQ(readError(kArm + " trajectory t { key 0 0 0 0 0 }\n player p {\n  trajectory t\n  speed 2\n  fade 0.5\n"
                               "  dof elbow.rx 1\n }\n}\n"),
              "t.actor:16: 'fade' is for a clip's player, and player 'p' plays a trajectory");
    EXPECT_EQ(readError(player("  clip walk\n")),
              "t.actor:12: player 'p' plays clip 'walk', which the actor does not have");
    EXPECT_EQ(readError(player("  clip wave\n  clip wave\n")), "t.actor:14: 'clip' is given twice");
    EXPECT_EQ(readError(player("  clip wave\n  loop\n")), "t.actor:14: unknown keyword 'loop' in a player");
    EXPECT_EQ(readError(player("  clip wave\n  play sometimes\n")),
              "t.actor:14: 'sometimes' is not a play mode (once, loop, pingpong)");
    EXPECT_EQ(readError(player("  clip wave\n  weight 1.5\n")), "t.actor:14: 'weight' must be from 0 to 1");
    EXPECT_EQ(readError(player("  clip wave\n  fade -0.1\n")), "t.actor:14: 'fade' must be from 0 to 1");
    EXPECT_EQ(readError(player("  clip wave\n  time nan\n")), "t.actor:14: 'nan' is not a finite number");
    EXPECT_EQ(readError(player("  clip wave\n  speed\n")), "t.actor:14: 'speed' takes 1 value, not 0");
    EXPECT_EQ(readError(player("  clip wave\n  sway_window -1\n")), "t.actor:14: 'sway_window' must not be negative");
    EXPECT_EQ(readError(player("  clip wave\n  root_motion sideways\n")),
              "t.actor:14: 'sideways' is not a root motion (in_skeleton, to_transforms, in_place)");
    EXPECT_EQ(readError(player("  clip wave\n  root_motion in_place hip\n")),
              "t.actor:14: 'hip' is not a joint of the actor");
    EXPECT_EQ(readError(player("  clip wave\n  root_motion\n")), "t.actor:14: 'root_motion' takes 1 value, not 0");
    EXPECT_EQ(readError(player("  clip wave\n  dof knee.rx 1\n")), "t.actor:14: 'knee.rx' names no DOF of the actor");
    EXPECT_EQ(readError(player("  clip wave\n  dof elbow.rx 1\n  dof elbow.rx 0.5\n")),
              "t.actor:15: DOF 'elbow.rx' is given twice");
    EXPECT_EQ(readError(player("  clip wave\n  dof elbow.rx 2\n")), "t.actor:14: a DOF's weight must be from 0 to 1");
    EXPECT_EQ(readError(player("  clip wave\n  dof elbow.rx\n")), "t.actor:14: 'dof' takes 2 values, not 1");
    EXPECT_EQ(readError(player("  clip wave\n  disabled 1\n")), "t.actor:14: 'disabled' takes 0 values, not 1");
    EXPECT_EQ(readError(kArm + " player p\n}\n"), "t.actor:12: 'player' needs a block in braces");
    EXPECT_EQ(readError(kArm + " player { clip wave }\n}\n"), "t.actor:12: 'player' takes 1 value, not 0");
}

TEST(ActorPlayers, PlayATrajectoryWithAControllersStateAndAreWrittenBackSo)
{
    const ActorReadResult result =
        read(kArm + " trajectory patrol {\n  key 1 0 0 0 0\n  key 3 4 0 0 90\n }\n"
                    " player walking {\n  trajectory patrol\n  play loop\n  time 2\n  speed 0.5\n }\n"
                    " player waiting {\n  trajectory patrol\n  weight 0.25\n  disabled\n }\n}\n");
    ASSERT_TRUE(result) << result.error;
    ASSERT_EQ(result.document.players.size(), 2u);
    const PlayerDocument& walking = result.document.players[0];
    EXPECT_TRUE(walking.playsTrajectory());
    EXPECT_EQ(walking.trajectory, "patrol");
    EXPECT_TRUE(walking.clip.empty());
    EXPECT_TRUE(walking.playing);
    EXPECT_EQ(walking.playMode, PlayMode::Loop);
    EXPECT_EQ(walking.time, std::optional<double>(2.0));
    EXPECT_EQ(walking.speed, 0.5);
    const PlayerDocument& waiting = result.document.players[1];
    EXPECT_FALSE(waiting.playing);
    EXPECT_EQ(waiting.playMode, PlayMode::Once) << "a new TrajectoryPlayer's mode";
    EXPECT_FALSE(waiting.time.has_value()) << "starts at the first key, like a new player";
    EXPECT_EQ(waiting.weight, 0.25);
    EXPECT_FALSE(waiting.enabled);

    const std::string text = written(result.document);
    EXPECT_NE(text.find("    trajectory patrol {\n        key 1 0 0 0 0\n        key 3 4 0 0 90\n    }\n"
                        "    player walking {\n        trajectory patrol\n        play loop\n        time 2\n"
                        "        speed 0.5\n    }\n    player waiting {\n        trajectory patrol\n        paused\n"
                        "        weight 0.25\n        disabled\n    }\n}\n"),
              std::string::npos)
        << text;
    expectRewrittenTheSame(text);
}
