#include "ActorTextTestUtil"

#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

using namespace osgActor;
using namespace osgActor::test;

namespace {

const double kDegree = 3.14159265358979323846 / 180.0;

} // namespace

// --- refusals first: each names the file and the line ---

TEST(ActorReader, RefusesAFileWithoutHeaderOrOfANewerVersion)
{
    EXPECT_EQ(readError(""), "t.actor:1: the file must start with the header 'osgactor 1'");
    EXPECT_EQ(readError("\nactor a { joint b }"), "t.actor:2: the file must start with the header 'osgactor 1'");
    EXPECT_EQ(readError("osgactor 2\nactor a { joint b }"),
              "t.actor:1: format version 2 is newer than this reader's (1)");
    EXPECT_EQ(readError("osgactor 1.5\n"), "t.actor:1: the format version must be a whole number from 1");
    EXPECT_EQ(readError("osgactor 1\n"), "t.actor:1: the file has no 'actor' block");
}

TEST(ActorReader, RefusesATruncatedFile)
{
    EXPECT_EQ(readError("osgactor 1\nactor a {\n  joint b {\n    dof rx\n"),
              "t.actor:5: the file ends inside the block opened at line 3");
    EXPECT_EQ(readError("osgactor 1\nactor a {\n  joint b {\n    offset 1 2"),
              "t.actor:4: the file ends inside the block opened at line 3");
    EXPECT_EQ(readError("osgactor 1\nactor a {\n  joint b {\n    offset 1 2\n}}"),
              "t.actor:4: 'offset' takes 3 values, not 2");
}

TEST(ActorReader, RefusesUnknownKeywordsWhereverTheyAre)
{
    EXPECT_EQ(readError("osgactor 1\nactress a { }"), "t.actor:2: unknown keyword 'actress' at the top of the file");
    EXPECT_EQ(readError("osgactor 1\nactor a {\n  jiont b\n}"), "t.actor:3: unknown keyword 'jiont' in an actor");
    EXPECT_EQ(readError("osgactor 1\nactor a {\n joint b {\n  ofset 1 2 3\n }\n}"),
              "t.actor:4: unknown keyword 'ofset' in a joint");
    EXPECT_EQ(readError("osgactor 1\nactor a {\n joint b {\n  dof rx mni 3\n }\n}"),
              "t.actor:4: unknown DOF attribute 'mni' (min, max, default, weight, value)");
    EXPECT_EQ(readError("osgactor 1\nactor a {\n joint b {\n  shape box {\n   size 1 1 1\n   colour 1 0 0\n }\n}\n}"),
              "t.actor:6: unknown keyword 'colour' in a shape");
    EXPECT_EQ(readError("osgactor 1\nactor a {\n joint b {\n  shape blob { radius 1 }\n }\n}"),
              "t.actor:4: 'blob' is not a shape (box, sphere, capsule, cylinder, cone)");
    EXPECT_EQ(readError("osgactor 1\nactor a {\n joint b {\n  euler XYX\n }\n}"),
              "t.actor:4: 'XYX' is not an Euler order (XYZ, XZY, YXZ, YZX, ZXY, ZYX)");
    EXPECT_EQ(readError("osgactor 1\nactor a {\n bounds tight\n joint b\n}"),
              "t.actor:3: 'tight' is not a bound mode (follows_pose, covers_rotations)");
}

TEST(ActorReader, RefusesDuplicateAndUnknownJointsAndCycles)
{
    const std::string duplicate = "osgactor 1\nactor a {\n joint b {\n  joint c\n }\n joint c\n}";
    EXPECT_EQ(readError(duplicate), "t.actor:6: actor 'a': joint name 'c' is used twice");
    const std::string unknown = "osgactor 1\nactor a {\n joint b\n joint c {\n  parent d\n }\n}";
    EXPECT_EQ(readError(unknown), "t.actor:4: actor 'a': joint 'c' names an unknown parent 'd'");
    const std::string cycle =
        "osgactor 1\nactor a {\n joint r\n joint b {\n  parent c\n }\n joint c {\n  parent b\n }\n}";
    const std::string error = readError(cycle);
    EXPECT_EQ(error.rfind("t.actor:4: actor 'a': the joints form a parent cycle: ", 0), 0u) << error;
    EXPECT_EQ(readError("osgactor 1\nactor a {\n joint b {\n  joint c {\n   parent b\n  }\n }\n}"),
              "t.actor:5: a nested joint's parent is the joint it is nested in; 'parent' is for joints at the "
              "actor's level");
    EXPECT_EQ(readError("osgactor 1\nactor a {\n}"), "t.actor:2: actor 'a': has no joints");
}

TEST(ActorReader, RefusesBadNumbersAndNaN)
{
    EXPECT_EQ(readError("osgactor 1\nactor a {\n joint b {\n  offset 1 2x 3\n }\n}"),
              "t.actor:4: '2x' is not a number");
    EXPECT_EQ(readError("osgactor 1\nactor a {\n joint b {\n  offset 1 nan 3\n }\n}"),
              "t.actor:4: 'nan' is not a finite number");
    EXPECT_EQ(readError("osgactor 1\nactor a {\n joint b {\n  dof rx\n  dof ry max inf\n }\n}"),
              "t.actor:5: 'inf' is not a finite number");
    EXPECT_EQ(readError("osgactor 1\nactor a {\n joint b {\n  offset 1 \"2\" 3\n }\n}"),
              "t.actor:4: \"2\" is a string, not a number");
    EXPECT_EQ(readError("osgactor 1\nactor a {\n joint b {\n  rotation 90 0 0 0\n }\n}"),
              "t.actor:4: the rotation axis is zero, or too long for a double");
    EXPECT_EQ(readError("osgactor 1\nactor a {\n joint b {\n  offset 1e-400 0 0\n }\n}"),
              "t.actor:4: '1e-400' is too small for a double (it would read as 0)");
}

TEST(ActorReader, RefusesWhatTheBuilderRefusesAtTheJointsLine)
{
    EXPECT_EQ(readError("osgactor 1\nactor a {\n joint b\n joint c {\n  dof rx min 10 max -10\n }\n}"),
              "t.actor:4: actor 'a': DOF 'c.rx' has its minimum 0.174533 above its maximum -0.174533")
        << "the builder speaks in radians";
    EXPECT_EQ(readError("osgactor 1\nactor a {\n joint b {\n  dof rx max 150 value 151\n }\n}"),
              "t.actor:4: the value of DOF 'rx' lies outside its limits");
    EXPECT_EQ(readError("osgactor 1\nactor a {\n joint b {\n  dof rx\n  dof rx\n }\n}"),
              "t.actor:5: DOF 'rx' is given twice");
    EXPECT_EQ(readError("osgactor 1\nactor a {\n joint b {\n  offset 1 1 1\n  offset 1 1 1\n }\n}"),
              "t.actor:5: 'offset' is given twice");
}

TEST(ActorReader, RefusesIncompleteShapes)
{
    EXPECT_EQ(readError("osgactor 1\nactor a {\n joint b {\n  shape box\n }\n}"),
              "t.actor:4: a box needs a 'size' of three lengths greater than zero");
    EXPECT_EQ(readError("osgactor 1\nactor a {\n joint b {\n  shape cone { radius 1 }\n }\n}"),
              "t.actor:4: a cone needs a 'height'");
    EXPECT_EQ(readError("osgactor 1\nactor a {\n joint b {\n  shape sphere { radius 1; height 2 }\n }\n}"),
              "t.actor:4: 'height' does not apply to a sphere");
    EXPECT_EQ(readError("osgactor 1\nactor a {\n joint b {\n  shape sphere { radius -1 }\n }\n}"),
              "t.actor:4: 'radius' must be greater than zero");
    EXPECT_EQ(readError("osgactor 1\nactor a {\n joint b {\n  shape sphere { radius 1; color 2 0 0 }\n }\n}"),
              "t.actor:4: colour components lie between 0 and 1");
}

// --- what a good file gives ---

TEST(ActorReader, ReadsJointsNestedWithDegreesTurnedIntoRadians)
{
    const ActorReadResult result = read(R"(osgactor 1
# an arm
actor "test arm" {
    pre_translation 1 2 3
    post_rotation 90 0 0 1
    joint base {
        offset 0 0 1
        dof rz min -90 max 90 default 10 weight 2
        joint "upper arm" {
            rotation 180 1 0 0
            euler ZYX
            translation_mode before_rotation
            dof rx value 30
            dof tx min 0 max 0.5 default 0.25
            hidden
            shape capsule { radius 0.1; height 0.5; position 0 0 0.25; color 1 0 0 0.5 }
            model "sword.osgt" { scale 2 }
        }
    }
}
)");
    ASSERT_TRUE(result) << result.error;
    const ActorDefinition& def = *result.definition;
    EXPECT_EQ(def.getName(), "test arm");
    ASSERT_EQ(def.getNumJoints(), 2u);
    EXPECT_EQ(def.getJointName(1), "upper arm");
    EXPECT_EQ(def.getParent(1), 0);
    EXPECT_EQ(def.getOffsetTranslation(0), glm::dvec3(0, 0, 1));
    const int rz = def.findDof("base.rz");
    ASSERT_GE(rz, 0);
    EXPECT_DOUBLE_EQ(def.getDofMin(rz), -90 * kDegree);
    EXPECT_DOUBLE_EQ(def.getDofMax(rz), 90 * kDegree);
    EXPECT_DOUBLE_EQ(def.getDofDefault(rz), 10 * kDegree);
    EXPECT_EQ(def.getDofWeight(rz), 2.0);
    const int tx = def.findDof("upper arm.tx");
    ASSERT_GE(tx, 0);
    EXPECT_EQ(def.getDofMin(tx), 0.0) << "translations stay in model units";
    EXPECT_EQ(def.getDofMax(tx), 0.5);
    EXPECT_EQ(def.getDofDefault(tx), 0.25);
    EXPECT_TRUE(std::isinf(def.getDofMax(def.findDof("upper arm.rx")))) << "no limit written, none set";
    EXPECT_EQ(def.getEulerOrder(1), EulerOrder::ZYX);
    EXPECT_EQ(def.getTranslationMode(1), TranslationMode::BeforeRotation);
    // 180 degrees about X: the quaternion (0, 1, 0, 0) up to sign.
    const glm::dquat& r = def.getOffsetRotation(1);
    EXPECT_NEAR(std::abs(r.x), 1.0, 1e-15);
    EXPECT_NEAR(r.w, 0.0, 1e-15);

    const ActorDocument& doc = result.document;
    EXPECT_EQ(doc.preTranslation, glm::dvec3(1, 2, 3));
    EXPECT_NEAR(doc.postRotation.z, std::sqrt(0.5), 1e-15);
    ASSERT_EQ(doc.joints.size(), 2u);
    const JointDocument& upper = doc.joints[1];
    EXPECT_TRUE(upper.hidden);
    ASSERT_TRUE(upper.values[0].has_value());
    EXPECT_DOUBLE_EQ(*upper.values[0], 30 * kDegree);
    EXPECT_FALSE(upper.values[3].has_value());
    ASSERT_EQ(upper.geometry.size(), 2u);
    EXPECT_EQ(upper.geometry[0].kind, GeometryKind::Capsule);
    EXPECT_EQ(upper.geometry[0].radius, 0.1);
    EXPECT_EQ(upper.geometry[0].height, 0.5);
    EXPECT_EQ(upper.geometry[0].position, glm::dvec3(0, 0, 0.25));
    EXPECT_EQ(upper.geometry[0].color, glm::dvec4(1, 0, 0, 0.5));
    EXPECT_EQ(upper.geometry[0].line, 16);
    EXPECT_EQ(upper.geometry[1].kind, GeometryKind::Model);
    EXPECT_EQ(upper.geometry[1].file, "sword.osgt");
    EXPECT_EQ(upper.geometry[1].scale, 2.0);
}

TEST(ActorReader, ReadsClipsAndIkChainsSideBySide)
{
    // IK chains are read in detail by tests/ik/test_ik_format.cpp.
    const ActorReadResult result = read("osgactor 1\nactor a {\n joint b { dof rz }\n clip walk {\n"
                                        "  channel b.rz { key 0 10 }\n }\n joint c { parent b; offset 1 0 0; dof rz }\n"
                                        " ikchain arm { root b; effector c; solver ccd }\n}\n");
    ASSERT_TRUE(result) << result.error;
    EXPECT_TRUE(result.document.sections.empty()) << "nothing is kept verbatim";
    ASSERT_EQ(result.document.clips.size(), 1u);
    EXPECT_EQ(result.document.clips[0].clip->getName(), "walk");
    ASSERT_EQ(result.document.ikChains.size(), 1u);
    EXPECT_EQ(result.document.ikChains[0].spec.name, "arm");
    EXPECT_EQ(readError("osgactor 1\nactor a {\n joint b\n clip walk\n}"), "t.actor:4: 'clip' needs a block in braces");
}

// --- clips ---

namespace {

const std::string kClipActor = "osgactor 1\nactor a {\n joint b {\n  dof rz\n  dof tx\n }\n";

} // namespace

TEST(ActorReader, RefusesBadClips)
{
    EXPECT_EQ(readError(kClipActor + " clip wave {\n  channel b.rx { key 0 1 }\n }\n}\n"),
              "t.actor:8: channel 'b.rx' names no DOF of the actor");
    EXPECT_EQ(readError(kClipActor + " clip wave {\n  channel b.rz {\n   key 0 1\n   key 0 2\n  }\n }\n}\n"),
              "t.actor:10: key times must increase");
    EXPECT_EQ(readError(kClipActor + " clip wave {\n  channel b.rz { key 0 1 }\n  frame_rate 30\n }\n}\n"),
              "t.actor:9: a clip has either 'channel' blocks or frames, not both");
    EXPECT_EQ(readError(kClipActor + " clip wave {\n  channel b.rz { interpolation smooth; key 0 1 }\n }\n}\n"),
              "t.actor:8: 'smooth' is not an interpolation (step, linear, cubic)");
    EXPECT_EQ(readError(kClipActor + " clip wave {\n  channel b.rz\n }\n}\n"),
              "t.actor:8: channel 'b.rz' has no key");
    EXPECT_EQ(readError(kClipActor + " clip wave {\n  channel b.rz { key -1 0 }\n }\n}\n").rfind("t.actor:7: ", 0),
              0u) << "the clip builder's refusal, at the clip's line";
    EXPECT_EQ(readError(kClipActor + " clip walk {\n  frame_rate 30\n  channels b.rz b.tx\n  frame 1 2 3\n }\n}\n"),
              "t.actor:10: 'frame' takes 2 values, not 3");
    EXPECT_EQ(readError(kClipActor + " clip walk {\n  channels b.rz\n  frame 1\n }\n}\n"),
              "t.actor:7: a clip of frames needs a 'frame_rate'");
    EXPECT_EQ(readError(kClipActor + " clip walk {\n  frame_rate 30\n  frame 1\n }\n}\n"),
              "t.actor:9: 'frame' must follow 'channels'");
    EXPECT_EQ(readError(kClipActor + " clip w { channel b.rz { key 0 1 } }\n clip w { channel b.rz { key 0 1 } }\n}\n"),
              "t.actor:8: clip 'w' is given twice");
    EXPECT_EQ(readError(kClipActor + " clip w {\n  key 0 1\n }\n}\n"), "t.actor:8: unknown keyword 'key' in a clip");
    EXPECT_EQ(readError(kClipActor + " clip w {\n  file \"walk.bvh\"\n  channel b.rz { key 0 1 }\n }\n}\n"),
              "t.actor:7: clip 'w' reads its motion from a file, so it has no channels or frames of its own");
    EXPECT_EQ(readError(kClipActor + " clip w {\n  file \"walk.fbx\"\n }\n}\n"),
              "t.actor:8: 'walk.fbx': a clip's file must be motion capture, BVH (.bvh) or AMC (.amc), or a rigged "
              "model's animation (.gltf, .glb)");
    EXPECT_EQ(readError(kClipActor + " clip w {\n  file \"walk.amc\"\n }\n}\n"),
              "t.actor:8: 'walk.amc': an AMC motion needs its ASF skeleton: 'skeleton \"x.asf\"' in a block after the "
              "file name");
    EXPECT_EQ(readError(kClipActor + " clip w {\n  file \"a.bvh\"\n  file \"b.bvh\"\n }\n}\n").rfind("t.actor:9: ", 0), 0u);
    EXPECT_EQ(readError(kClipActor + " clip w { file \"a.bvh\" }\n clip w { file \"b.bvh\" }\n}\n"),
              "t.actor:8: clip 'w' is given twice");
}

TEST(ActorReader, LeavesAClipFileForTheSceneLoaderAndWritesItBack)
{
    const ActorReadResult result = read(kClipActor + " clip walk {\n  play pingpong\n  file \"motion/Walk.BVH\"\n }\n}\n");
    ASSERT_TRUE(result) << result.error;
    ASSERT_EQ(result.document.clips.size(), 1u);
    const ClipDocument& clip = result.document.clips[0];
    EXPECT_EQ(clip.clip, nullptr) << "read when the actor is made, where files are found";
    EXPECT_EQ(clip.file, "motion/Walk.BVH");
    EXPECT_EQ(clip.fileOptions.name, "walk");
    EXPECT_EQ(clip.line, 7);
    EXPECT_TRUE(clip.play);
    EXPECT_EQ(clip.playMode, PlayMode::PingPong);

    std::ostringstream written;
    writeActor(written, result.document);
    EXPECT_NE(written.str().find("clip walk {\n        play pingpong\n        file \"motion/Walk.BVH\"\n    }"),
              std::string::npos)
        << written.str();
    const ActorReadResult again = read(written.str());
    ASSERT_TRUE(again) << again.error;
    EXPECT_EQ(again.document.clips.at(0).file, "motion/Walk.BVH");
}

TEST(ActorReader, RefusesClipFileOptionsThatDoNotApplyOrAreBroken)
{
    const auto fileBlock = [](const std::string& file, const std::string& options) {
        return readError(kClipActor + " clip w {\n  file \"" + file + "\" {\n   " + options + "\n  }\n }\n}\n");
    };
    EXPECT_EQ(fileBlock("walk.bvh", "frame_rate 60"),
              "t.actor:9: 'frame_rate' is for AMC files, and 'walk.bvh' is BVH");
    EXPECT_EQ(fileBlock("walk.bvh", "skeleton \"walk.asf\""),
              "t.actor:9: 'skeleton' is for AMC files, and 'walk.bvh' is BVH");
    EXPECT_EQ(fileBlock("walk.amc", "skeleton \"walk.asf\"\n   drop_first_frame"),
              "t.actor:10: 'drop_first_frame' is for BVH files, and 'walk.amc' is AMC");
    EXPECT_EQ(fileBlock("walk.amc", "skeleton \"walk.asf\"\n   absolute_root_position"),
              "t.actor:10: 'absolute_root_position' is for BVH files, and 'walk.amc' is AMC");
    EXPECT_EQ(fileBlock("walk.amc", "skeleton \"walk.bvh\""),
              "t.actor:9: 'walk.bvh': an AMC motion's skeleton must be ASF (.asf)");
    EXPECT_EQ(fileBlock("walk.bvh", "scale 0"), "t.actor:9: 'scale' must be greater than zero");
    EXPECT_EQ(fileBlock("walk.bvh", "scale 1\n   scale 2"), "t.actor:10: 'scale' is given twice");
    EXPECT_EQ(fileBlock("walk.bvh", "up x"), "t.actor:9: 'x' is not an up axis (y, z)");
    EXPECT_EQ(fileBlock("walk.bvh", "loop"), "t.actor:9: unknown keyword 'loop' in a clip's file block");
    EXPECT_EQ(fileBlock("walk.bvh", "drop_first_frame 1"), "t.actor:9: 'drop_first_frame' takes 0 values, not 1");
    EXPECT_EQ(fileBlock("walk.bvh", "animation \"run\""),
              "t.actor:9: 'animation' is for rigged model files (.gltf, .glb), and 'walk.bvh' is BVH");
    EXPECT_EQ(fileBlock("hero.gltf", "scale 2"),
              "t.actor:9: 'scale' is not for a rigged model's animation, and 'hero.gltf' is one");
    EXPECT_EQ(fileBlock("hero.glb", "skeleton \"walk.asf\""),
              "t.actor:9: 'skeleton' is not for a rigged model's animation, and 'hero.glb' is one");
    EXPECT_EQ(fileBlock("hero.gltf", "animation"), "t.actor:9: 'animation' takes 1 value, not 0");
}

TEST(ActorReader, ReadsARiggedModelsAnimationAsAClipFileAndWritesItBack)
{
    const ActorReadResult result =
        read(kClipActor + " clip walk {\n  file \"hero.gltf\" {\n   animation \"Walk Cycle\"\n   up z\n  }\n }\n}\n");
    ASSERT_TRUE(result) << result.error;
    const MotionFileOptions& options = result.document.clips.at(0).fileOptions;
    EXPECT_EQ(options.name, "walk");
    EXPECT_EQ(options.animation, "Walk Cycle");
    EXPECT_EQ(options.fileUpAxis, UpAxis::Z);

    std::ostringstream written;
    writeActor(written, result.document);
    EXPECT_NE(written.str().find("    clip walk {\n        file \"hero.gltf\" {\n            animation \"Walk Cycle\"\n"
                                 "            up z\n        }\n    }"),
              std::string::npos)
        << written.str();
    const ActorReadResult again = read(written.str());
    ASSERT_TRUE(again) << again.error;
    EXPECT_EQ(again.document.clips.at(0).fileOptions.animation, "Walk Cycle");
    EXPECT_EQ(again.document.clips.at(0).fileOptions.fileUpAxis, UpAxis::Z);
}

TEST(ActorReader, ReadsClipFileOptionsAndWritesBackThoseThatAreNotDefaults)
{
    const ActorReadResult result =
        read(kClipActor + " clip run {\n  file \"motion/02_01.amc\" {\n   skeleton \"motion/02.asf\"\n"
                          "   scale 0.05\n   up z\n   frame_rate 60\n  }\n }\n clip walk {\n  file \"walk.bvh\" {\n"
                          "   drop_first_frame\n   absolute_root_position\n  }\n }\n}\n");
    ASSERT_TRUE(result) << result.error;
    ASSERT_EQ(result.document.clips.size(), 2u);
    const MotionFileOptions& amc = result.document.clips[0].fileOptions;
    EXPECT_EQ(amc.name, "run");
    EXPECT_EQ(amc.skeletonFile, "motion/02.asf");
    EXPECT_EQ(amc.scale, 0.05);
    EXPECT_EQ(amc.fileUpAxis, UpAxis::Z);
    EXPECT_EQ(amc.amcFrameRate, 60.0);
    EXPECT_FALSE(amc.dropFirstFrame);
    const MotionFileOptions& bvh = result.document.clips[1].fileOptions;
    EXPECT_EQ(bvh.scale, 1.0);
    EXPECT_EQ(bvh.fileUpAxis, UpAxis::Y);
    EXPECT_TRUE(bvh.dropFirstFrame);
    EXPECT_TRUE(bvh.absoluteRootPosition);

    std::ostringstream written;
    writeActor(written, result.document);
    EXPECT_NE(written.str().find("    clip run {\n        file \"motion/02_01.amc\" {\n"
                                 "            skeleton \"motion/02.asf\"\n            scale 0.05\n            up z\n"
                                 "            frame_rate 60\n        }\n    }"),
              std::string::npos)
        << written.str();
    const ActorReadResult again = read(written.str());
    ASSERT_TRUE(again) << again.error;
    const MotionFileOptions& reread = again.document.clips.at(1).fileOptions;
    EXPECT_TRUE(reread.dropFirstFrame);
    EXPECT_TRUE(reread.absoluteRootPosition);
    EXPECT_EQ(again.document.clips.at(0).fileOptions.skeletonFile, "motion/02.asf");
    EXPECT_EQ(again.document.clips.at(0).fileOptions.amcFrameRate, 60.0);
}

TEST(ActorReader, ReadsTrajectoriesInDegreesWithTheirPlayersStateAndWritesThemBack)
{
    const ActorReadResult result =
        read(kClipActor + " trajectory patrol {\n  play loop\n  speed 1.5\n  key 0 0 0 0 0\n  key 2 4 0 0.5 90\n }\n"
                          " trajectory waiting {\n  play pingpong\n  paused\n  key 1 1 2 3 -45\n }\n"
                          " trajectory route { file \"paths/route.csv\" }\n}\n");
    ASSERT_TRUE(result) << result.error;
    ASSERT_EQ(result.document.trajectories.size(), 3u);
    const TrajectoryDocument& patrol = result.document.trajectories[0];
    ASSERT_TRUE(patrol.trajectory);
    EXPECT_EQ(patrol.trajectory->getName(), "patrol");
    EXPECT_EQ(patrol.line, 7);
    EXPECT_TRUE(patrol.play);
    EXPECT_EQ(patrol.playMode, PlayMode::Loop);
    EXPECT_EQ(patrol.speed, 1.5);
    ASSERT_EQ(patrol.trajectory->getKeys().size(), 2u);
    const TrajectoryKey& second = patrol.trajectory->getKeys()[1];
    EXPECT_EQ(second.time, 2.0);
    EXPECT_EQ(second.position, glm::dvec3(4.0, 0.0, 0.5));
    EXPECT_NEAR(second.heading, glm::half_pi<double>(), 1e-15);
    const TrajectoryDocument& waiting = result.document.trajectories[1];
    EXPECT_FALSE(waiting.play) << "paused: the player waits, in its mode";
    EXPECT_EQ(waiting.playMode, PlayMode::PingPong);
    const TrajectoryDocument& route = result.document.trajectories[2];
    EXPECT_EQ(route.trajectory, nullptr) << "read when the actor is made, where files are found";
    EXPECT_EQ(route.file, "paths/route.csv");
    EXPECT_EQ(route.name(), "route");
    EXPECT_FALSE(route.play);

    std::ostringstream written;
    writeActor(written, result.document);
    EXPECT_NE(written.str().find("    trajectory patrol {\n        play loop\n        speed 1.5\n"
                                 "        key 0 0 0 0 0\n        key 2 4 0 0.5 90\n    }\n    trajectory waiting {\n"
                                 "        play pingpong\n        paused\n        key 1 1 2 3 -45\n    }\n    trajectory route {\n"
                                 "        file \"paths/route.csv\"\n    }\n"),
              std::string::npos)
        << written.str();
    expectRewrittenTheSame(written.str());
}

TEST(ActorReader, KeysOneRoundingStepApartStayApartWhenWritten)
{
    // Every number is written as the shortest text that reads back as the same double, however close its neighbour.
    const ActorReadResult result =
        read(kClipActor + " clip c { channel b.rz {\n  key 1 0\n  key 1.0000000000000002 1\n } }\n"
                          " trajectory t {\n  key 1.0000000000001 0 0 0 0\n  key 1.0000000000002 1 1 1 1\n }\n}\n");
    ASSERT_TRUE(result) << result.error;
    std::ostringstream written;
    writeActor(written, result.document);
    EXPECT_NE(written.str().find("key 1 0\n            key 1.0000000000000002 1\n"), std::string::npos)
        << written.str();
    EXPECT_NE(written.str().find("key 1.0000000000001 0 0 0 0\n        key 1.0000000000002 1 1 1 1\n"),
              std::string::npos);
    expectRewrittenTheSame(written.str());
}

TEST(ActorReader, RefusesBrokenTrajectories)
{
    EXPECT_EQ(readError(kClipActor + " trajectory p {\n  key 0 0 0 0 0\n  key 0 1 0 0 0\n }\n}\n"),
              "t.actor:9: key times must increase (0 follows 0)");
    EXPECT_EQ(readError(kClipActor + " trajectory p {\n  key 0 0 0 0\n }\n}\n"),
              "t.actor:8: 'key' takes 5 values, not 4");
    EXPECT_EQ(readError(kClipActor + " trajectory p {\n  key 0 0 nan 0 0\n }\n}\n").rfind("t.actor:8: ", 0), 0u);
    EXPECT_EQ(readError(kClipActor + " trajectory p {\n  play loop\n }\n}\n"), "t.actor:7: trajectory 'p' has no key");
    EXPECT_EQ(readError(kClipActor + " trajectory p {\n  play sometimes\n  key 0 0 0 0 0\n }\n}\n"),
              "t.actor:8: 'sometimes' is not a play mode (once, loop, pingpong)");
    EXPECT_EQ(readError(kClipActor + " trajectory p {\n  file \"p.csv\"\n  key 0 0 0 0 0\n }\n}\n"),
              "t.actor:7: trajectory 'p' reads its keys from a file, so it has no keys of its own");
    EXPECT_EQ(readError(kClipActor + " trajectory p {\n  file \"p.txt\"\n }\n}\n"),
              "t.actor:8: 'p.txt': a trajectory's file must be CSV (.csv)");
    EXPECT_EQ(readError(kClipActor + " trajectory p { key 0 0 0 0 0 }\n trajectory p { file \"p.csv\" }\n}\n"),
              "t.actor:8: trajectory 'p' is given twice");
    EXPECT_EQ(readError(kClipActor + " trajectory p {\n  heading 0\n }\n}\n"),
              "t.actor:8: unknown keyword 'heading' in a trajectory");
    EXPECT_EQ(readError(kClipActor + " trajectory p\n}\n"), "t.actor:7: 'trajectory' needs a block in braces");
}

TEST(ActorReader, ReadsKeyedClipsInDegreesAndSeconds)
{
    const ActorReadResult result =
        read(kClipActor + " clip wave {\n  channel b.rz {\n   interpolation cubic\n   key 0 0\n   key 0.5 90\n"
                          "   key 1 0\n  }\n  channel b.tx { key 0 0.25 }\n }\n}\n");
    ASSERT_TRUE(result) << result.error;
    ASSERT_EQ(result.document.clips.size(), 1u);
    const Clip& clip = *result.document.clips[0].clip;
    EXPECT_EQ(clip.getName(), "wave");
    EXPECT_FALSE(clip.isUniform());
    EXPECT_EQ(clip.getDuration(), 1.0);
    ASSERT_EQ(clip.getNumChannels(), 2u);
    EXPECT_EQ(clip.getChannel(0).target, "b.rz");
    EXPECT_EQ(clip.getChannel(0).interpolation, Interpolation::Cubic);
    EXPECT_TRUE(clip.getChannel(0).angular);
    ASSERT_EQ(clip.getNumKeys(0), 3u);
    EXPECT_EQ(clip.getKeyTime(0, 1), 0.5);
    EXPECT_DOUBLE_EQ(clip.getKeyValue(0, 1), 90 * kDegree);
    EXPECT_EQ(clip.getChannel(1).interpolation, Interpolation::Linear);
    EXPECT_EQ(clip.getKeyValue(1, 0), 0.25) << "translations stay in model units";
}

TEST(ActorReader, ReadsClipsOfFrames)
{
    const ActorReadResult result = read(kClipActor + " clip walk {\n  frame_rate 4\n  channels b.tx b.rz\n"
                                                     "  frame 0 0\n  frame 0.1 45\n  frame 0.2 90\n }\n}\n");
    ASSERT_TRUE(result) << result.error;
    const Clip& clip = *result.document.clips.at(0).clip;
    EXPECT_TRUE(clip.isUniform());
    EXPECT_EQ(clip.getFrameRate(), 4.0);
    ASSERT_EQ(clip.getNumFrames(), 3u);
    EXPECT_EQ(clip.getDuration(), 0.5);
    EXPECT_EQ(clip.getFrame(1)[0], 0.1);
    EXPECT_DOUBLE_EQ(clip.getFrame(2)[1], 90 * kDegree);
}

TEST(ActorReader, AcceptsFlatJointsWithParentInAnyOrder)
{
    const ActorReadResult result = read("osgactor 1\nactor a {\n joint c { parent b; offset 1 0 0 }\n joint b\n}\n");
    ASSERT_TRUE(result) << result.error;
    EXPECT_EQ(result.definition->getJointName(0), "b") << "the definition is parent-first";
    EXPECT_EQ(result.definition->getParent(1), 0);
}

TEST(ActorReader, RefusesBrokenCullModesAndUpdatePolicies)
{
    const std::string head = "osgactor 1\nactor a {\n joint b\n ";
    EXPECT_EQ(readError(head + "cull fast\n}"), "t.actor:4: 'fast' is not a cull mode (as_one, node_by_node)");
    EXPECT_EQ(readError(head + "cull as_one\n cull node_by_node\n}"), "t.actor:5: 'cull' is given twice");
    EXPECT_EQ(readError(head + "update_policy\n}"), "t.actor:4: 'update_policy' needs a block in braces");
    EXPECT_EQ(readError(head + "update_policy { only_when_seen }\n update_policy { }\n}"),
              "t.actor:5: 'update_policy' is given twice");
    EXPECT_EQ(readError(head + "update_policy {\n  only_when_seen\n  only_when_seen\n }\n}"),
              "t.actor:6: 'only_when_seen' is given twice");
    EXPECT_EQ(readError(head + "update_policy {\n  max_distance -1\n }\n}"),
              "t.actor:5: 'max_distance' must not be negative");
    EXPECT_EQ(readError(head + "update_policy {\n  max_distance inf\n }\n}"), "t.actor:5: 'inf' is not a finite number");
    EXPECT_EQ(readError(head + "update_policy {\n  half_rate_below_pixels 1e39\n }\n}"),
              "t.actor:5: 'half_rate_below_pixels' 1e39 is not a size a float holds");
    // So small a float would hold 0, which means "off": refused rather than changed.
    EXPECT_EQ(readError(head + "update_policy {\n  quarter_rate_below_pixels 1e-50\n }\n}"),
              "t.actor:5: 'quarter_rate_below_pixels' 1e-50 is not a size a float holds");
    EXPECT_EQ(readError(head + "update_policy {\n  every_frame\n }\n}"),
              "t.actor:5: unknown keyword 'every_frame' in 'update_policy'");
}

TEST(ActorReader, ReadsTheCullModeAndTheUpdatePolicy)
{
    const ActorReadResult plain = read("osgactor 1\nactor a {\n joint b\n}\n");
    ASSERT_TRUE(plain) << plain.error;
    EXPECT_FALSE(plain.document.cullNodeByNode);
    EXPECT_TRUE(plain.document.updatePolicy.isDefault());

    const ActorReadResult set = read("osgactor 1\nactor a {\n joint b\n cull node_by_node\n update_policy {\n"
                                     "  only_when_seen\n  max_distance 40\n  half_rate_below_pixels 0.1\n"
                                     "  quarter_rate_below_pixels 12\n }\n}\n");
    ASSERT_TRUE(set) << set.error;
    EXPECT_TRUE(set.document.cullNodeByNode);
    EXPECT_TRUE(set.document.updatePolicy.onlyWhenSeen);
    EXPECT_EQ(set.document.updatePolicy.maxDistance, 40.0);
    EXPECT_EQ(set.document.updatePolicy.halfRateBelowPixels, 0.1f) << "held as the float nearest 0.1";
    EXPECT_EQ(set.document.updatePolicy.quarterRateBelowPixels, 12.0f);
    const ActorReadResult asOne = read("osgactor 1\nactor a {\n joint b\n cull as_one\n}\n");
    ASSERT_TRUE(asOne) << asOne.error;
    EXPECT_FALSE(asOne.document.cullNodeByNode);
}
