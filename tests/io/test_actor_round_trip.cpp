/* Whatever the .actor reader accepts, the writer writes and the reader reads back as an equal document
 * (documentDifference), section by section, with the numbers at the edges of what a double holds; and what the
 * format cannot hold is refused with the line, not changed. */
#include "ActorTextTestUtil"

#include <osgActor/io/DocumentDifference>
#include <osgActor/text/Numbers>

#include <cmath>

using namespace osgActor;
using namespace osgActor::test;

namespace {

/** Reads text, writes it, reads that back: the two documents are the same, and so is a second writing. */
void expectRoundTrip(const std::string& text)
{
    const ActorReadResult first = read(text);
    ASSERT_TRUE(first) << first.error << "\n" << text;
    const std::string writtenText = written(first.document);
    const ActorReadResult second = read(writtenText);
    ASSERT_TRUE(second) << second.error << "\n" << writtenText;
    EXPECT_EQ(documentDifference(first.document, second.document), "") << writtenText;
    EXPECT_EQ(written(second.document), writtenText);
}

double valueOf(const std::string& text)
{
    double value = 0.0;
    EXPECT_TRUE(parseNumber(text, value)) << text;
    return value;
}

/** The edge values: the smallest subnormal, a subnormal, the smallest normal, 1e+-300, -0, the largest double. */
const char* const kEdges[] = {"5e-324", "-2.5e-320", "2.2250738585072014e-308", "1e-300", "-1e300", "-0",
                              "1.7976931348623157e+308", "0.30000000000000004", "1e+22", "123456789.98765433"};

// Lines 1-5: a one-joint actor whose joint turns about Z and slides along X.
const std::string kActor = "osgactor 1\nactor a {\n joint b {\n  dof rz\n  dof tx\n }\n";

} // namespace

// --- what the format cannot hold is refused, with the line ---

TEST(ActorRoundTrip, AValueBeyondWhatAPoseHoldsIsRefusedNotChanged)
{
    // 1e308 degrees are 1.7e306 radians, beyond what a pose holds (kMaxDofMagnitude): written back it would be
    // the clamped 5.7e151, so it is refused.
    EXPECT_EQ(readError("osgactor 1\nactor a {\n joint b {\n  dof rx value 1e308\n }\n}\n"),
              "t.actor:4: the value of DOF 'rx' lies beyond what a pose holds (+-1e+150 radians)");
    EXPECT_EQ(readError("osgactor 1\nactor a {\n joint b {\n  dof tx min -1e300 max 1e300 value 1e200\n }\n}\n"),
              "t.actor:4: the value of DOF 'tx' lies beyond what a pose holds (+-1e+150)");
    EXPECT_EQ(readError("osgactor 1\nactor a {\n pre_translation 0 1e151 0\n joint b\n}\n"),
              "t.actor:3: 'pre_translation' 1e151 lies beyond what an actor holds (+-1e+150)");
    EXPECT_EQ(readError("osgactor 1\nactor a {\n post_translation -1e300 0 0\n joint b\n}\n"),
              "t.actor:3: 'post_translation' -1e300 lies beyond what an actor holds (+-1e+150)");
}

TEST(ActorRoundTrip, ANumberTooSmallForADoubleIsRefusedNotReadAsZero)
{
    EXPECT_EQ(readError(kActor + " clip c {\n  frame_rate 1e-400\n  channels b.rz\n  frame 0\n }\n}\n"),
              "t.actor:8: '1e-400' is too small for a double (it would read as 0)");
}

TEST(ActorRoundTrip, ControlCharactersAreRefusedWithTheLine)
{
    EXPECT_EQ(readError(std::string("osgactor 1\nactor a {\n joint \"b\0c\"\n}\n", 31)),
              "t.actor:3: a control character (0x00) in the text: names and words hold printable characters only (a "
              "binary or damaged file?)");
    EXPECT_NE(readError("osgactor 1\nactor a {\n joint b\x1b[1m\n}\n").find("t.actor:3: a control character (0x1B)"),
              std::string::npos);
    // A newline cannot be inside a name: the string ends at the end of its line.
    EXPECT_EQ(readError("osgactor 1\nactor a {\n joint \"b\nc\"\n}\n"),
              "t.actor:3: the string that starts here is not closed on its line");
}

// --- round trips, section by section ---

TEST(ActorRoundTrip, AFrameRateOf1eMinus300IsWrittenAs1eMinus300)
{
    const std::string text = kActor + " clip c {\n  frame_rate 1e-300\n  channels b.rz\n  frame 0\n }\n}\n";
    expectRoundTrip(text);
    EXPECT_NE(written(read(text).document).find("frame_rate 1e-300\n"), std::string::npos);
}

TEST(ActorRoundTrip, DefinitionsKeepEdgeOffsetsLimitsDefaultsAndWeights)
{
    for (const char* edge : kEdges)
    {
        const std::string e = edge;
        // Offsets are lengths within +-1e150; limits take any double; weights any number from 0.
        const bool offset = std::abs(valueOf(e)) <= 1e150;
        const bool positive = e.front() != '-';
        std::string joint = " joint \"" + e + "\" {\n";
        if (offset) joint += "  offset " + e + " " + e + " 1\n";
        joint += "  dof rx min " + (positive ? "-" + e : e) + " max " + (positive ? e : e.substr(1)) + "\n";
        joint += "  dof tx min -1.7976931348623157e+308 max 1.7976931348623157e+308" +
                 (offset ? " default " + e : std::string()) + "\n";
        if (positive) joint += "  dof ty weight " + e + "\n";
        joint += " }\n";
        SCOPED_TRACE(edge);
        expectRoundTrip("osgactor 1\nactor a {\n" + joint + "}\n");
    }
}

TEST(ActorRoundTrip, RotationsComeBackExactlyAsAnAngleAndAxisOrAQuaternion)
{
    for (const char* rotation : {"90 0 0 1", "33.3 1 -0.25 0.7", "1e-300 1 0 0", "1e308 0 1 0", "-0 0 0 1",
                                 "179.99999999999997 0.1 0.2 0.3", "0.1 5e-324 1 0", "120 1 1 1", "70 1 0.3 0",
                                 "quaternion 0.5 0.5 0.5 0.5", "quaternion 0.7071 0 0 0.7071",
                                 "quaternion -1 0 0 0", "quaternion 2 0 0 0"})
    {
        SCOPED_TRACE(rotation);
        expectRoundTrip(std::string("osgactor 1\nactor a {\n pre_rotation ") + rotation + "\n post_rotation " +
                        rotation + "\n joint b {\n  rotation " + rotation + "\n  shape box {\n   size 1 1 1\n" +
                        "   rotation " + rotation + "\n  }\n }\n}\n");
    }
    // Angles and axes of short text are written as they were.
    const ActorReadResult read70 = read("osgactor 1\nactor a {\n joint b { rotation 70 1 0.3 0 }\n}\n");
    ASSERT_TRUE(read70) << read70.error;
    EXPECT_NE(written(read70.document).find("rotation 70 1 0.3 0\n"), std::string::npos);
}

TEST(ActorRoundTrip, PosesFlagsBoundsAndTransformsComeBackExactly)
{
    for (const char* edge : kEdges)
    {
        const std::string e = edge;
        const bool holdable = std::abs(valueOf(e)) <= 1e150;
        SCOPED_TRACE(edge);
        std::string text = "osgactor 1\nactor a {\n";
        if (holdable) text += " pre_translation " + e + " 0 " + e + "\n post_translation 0 " + e + " 1\n";
        text += " blocked\n bounds follows_pose\n joint b {\n  dof rz value " + (holdable ? e : "0.5") +
                "\n  dof tx value " + (holdable ? e : "-0") + "\n  hidden\n }\n}\n";
        expectRoundTrip(text);
    }
}

TEST(ActorRoundTrip, CullModesAndUpdatePoliciesComeBackExactly)
{
    // Distances take any finite double from 0; sizes on screen any float (the largest, the smallest denormal, one
    // that is not a short decimal).
    for (const char* distance : {"0", "5e-324", "0.30000000000000004", "1.7976931348623157e+308"})
        for (const char* pixels : {"0", "0.1", "1.401298464324817e-45", "3.4028234663852886e+38"})
        {
            SCOPED_TRACE(std::string(distance) + " " + pixels);
            expectRoundTrip(kActor + " cull node_by_node\n update_policy {\n  only_when_seen\n  max_distance " +
                            distance + "\n  half_rate_below_pixels " + pixels + "\n  quarter_rate_below_pixels " +
                            pixels + "\n }\n}\n");
        }
    // The defaults are not written; a policy that is not the default is.
    const ActorReadResult defaults =
        read(kActor + " cull as_one\n update_policy { max_distance 1e300 }\n}\n");
    ASSERT_TRUE(defaults) << defaults.error;
    const std::string text = written(defaults.document);
    EXPECT_EQ(text.find("cull"), std::string::npos) << text;
    EXPECT_NE(text.find("update_policy {\n        max_distance 1e+300\n    }"), std::string::npos) << text;
}

TEST(ActorRoundTrip, GeometryComesBackExactly)
{
    expectRoundTrip(kActor.substr(0, kActor.size() - 3) +
                    "  shape box { size 5e-324 1e300 0.30000000000000004; position -0 1e-300 -1e300; "
                    "color 0 1 0.1 0.30000000000000004 }\n"
                    "  shape cone { radius 2.2250738585072014e-308; height 1.7976931348623157e+308 }\n"
                    "  shape capsule { radius 1; height 2; color 0.5 0.5 0.5 }\n"
                    "  model \"tools/spanner.osgt\" { position 1 2 3; rotation 45 0 0 1; scale 1e-300 }\n }\n}\n");
}

TEST(ActorRoundTrip, ClipsOfKeysAndOfFramesComeBackExactly)
{
    std::string frames =
        " clip frames {\n  play pingpong\n  frame_rate 1.7976931348623157e+308\n  channels b.rz b.tx\n";
    std::string keys = " clip keys {\n  channel b.rz {\n   interpolation cubic\n";
    double time = 1.0;
    for (const char* edge : kEdges)
    {
        frames += std::string("  frame ") + edge + " " + edge + "\n";
        keys += "   key " + formatNumber(time) + " " + edge + "\n";
        time = std::nextafter(time, 2.0); // keys one rounding step apart
    }
    frames += " }\n";
    keys += "  }\n  channel b.tx {\n   interpolation step\n   key 0 -0\n   key 1e300 5e-324\n  }\n }\n";
    expectRoundTrip(kActor + frames + keys + "}\n");
}

TEST(ActorRoundTrip, ClipFilesKeepTheirOptions)
{
    expectRoundTrip(kActor + " clip walk {\n  play once\n  file \"walk.amc\" {\n   skeleton \"walk.asf\"\n"
                             "   scale 5e-324\n   up z\n   frame_rate 1e-300\n  }\n }\n"
                             " clip run { file \"run.bvh\" { drop_first_frame; absolute_root_position } }\n}\n");
}

TEST(ActorRoundTrip, JointMapsAndAClipsRetargetComeBack)
{
    const std::string maps = " jointmap { map b HumanoidRoot }\n jointmap studio { base cmu_bvh; map hip l_hip }\n";
    const std::string text = kActor + maps + " clip walk { file \"walk.bvh\"; retarget studio { ik off } }\n"
                                             " clip run { file \"run.bvh\"; retarget auto }\n}\n";
    expectRoundTrip(text);
    // The comparison sees the retarget statement: the same document without it differs there.
    const ActorReadResult with = read(text);
    const ActorReadResult without = read(kActor + maps + " clip walk { file \"walk.bvh\" }\n"
                                                         " clip run { file \"run.bvh\"; retarget auto }\n}\n");
    ASSERT_TRUE(with && without) << with.error << without.error;
    EXPECT_EQ(documentDifference(with.document, without.document).find("clip 'walk': retarget: yes against no"), 0u)
        << documentDifference(with.document, without.document);
}

TEST(ActorRoundTrip, TrajectoriesAndPlayersComeBackExactly)
{
    std::string trajectory = " trajectory path {\n  play pingpong\n  paused\n  speed -1e-300\n";
    double time = 0.0;
    for (const char* edge : kEdges)
    {
        // Positions place the actor, which holds them within +-1e150 (beyond is refused); headings take any angle.
        const std::string e = edge;
        const std::string p = std::abs(valueOf(e)) <= 1e150 ? e : (e.front() == '-' ? "-1e150" : "1e150");
        trajectory += "  key " + formatNumber(time) + " " + p + " -" + (p.front() == '-' ? p.substr(1) : p) +
                      " 0 " + e + "\n";
        time = time == 0.0 ? 5e-324 : time * 1e10;
    }
    trajectory += " }\n trajectory file { file \"path.csv\" }\n";
    const std::string players =
        " clip c { channel b.rz { key 0 0; key 1 1 } }\n"
        " player p {\n  clip c\n  play once\n  time -1.7976931348623157e+308\n  speed 1e-300\n  weight 5e-324\n"
        "  fade 0.30000000000000004\n  disabled\n  root_motion to_transforms b\n  sway_window 1e300\n"
        "  dof b.tx 2.2250738585072014e-308\n  dof b.rz 1\n }\n"
        " player q {\n  trajectory path\n  time -0\n  weight 0\n }\n";
    expectRoundTrip(kActor + trajectory + players + "}\n");
}

TEST(ActorRoundTrip, IkChainsComeBackExactly)
{
    expectRoundTrip("osgactor 1\nactor arm {\n joint s {\n  dof rz\n  joint e {\n   offset 1 0 0\n   dof rz\n"
                    "   joint h { offset 1e-300 0 -0 }\n  }\n }\n ikchain reach {\n  root s\n  effector h\n"
                    "  effector_offset 5e-324 -1e300 0.30000000000000004\n  solver ccd\n  iterations 1000000\n"
                    "  tolerance 0.99999999999999989\n  joint_weight e 1.7976931348623157e+308\n"
                    "  dof_weight s.rz 5e-324\n }\n ikchain fine {\n  root s\n  effector e\n"
                    "  tolerance 5e-324\n }\n}\n");
}

TEST(ActorRoundTrip, TheDataActorsComeBackExactly)
{
    for (const char* name : {"humanoid.actor", "insect.actor", "robot_arm.actor"})
    {
        std::ifstream in(std::string(OSGACTOR_TEST_DATA_DIR) + "/" + name);
        std::ostringstream text;
        text << in.rdbuf();
        SCOPED_TRACE(name);
        expectRoundTrip(text.str());
    }
}

TEST(ActorRoundTrip, JointsGivenInAnyOrderComeBackInTheDefinitionsOrder)
{
    // Flat joints with 'parent' statements, children before parents: read in the definition's order, parents first.
    const std::string text = "osgactor 1\nactor a {\n joint c { parent b }\n joint d { parent a }\n"
                             " joint b { parent a }\n joint a\n}\n";
    const ActorReadResult result = read(text);
    ASSERT_TRUE(result) << result.error;
    ASSERT_EQ(result.document.joints.size(), 4u);
    for (unsigned j = 0; j < 4; ++j)
        EXPECT_EQ(result.document.joints[j].spec.name, result.definition->getJointName(j));
    EXPECT_EQ(result.document.joints[0].spec.name, "a");
    expectRoundTrip(text);
    // A chain deeper than the writer nests (100), with a sibling after it, keeps its order too.
    std::string deep = "osgactor 1\nactor a {\n joint r\n";
    for (int j = 0; j < 150; ++j)
        deep += " joint j" + std::to_string(j) + " { parent " +
                (j == 0 ? std::string("r") : "j" + std::to_string(j - 1)) + " }\n";
    deep += " joint sibling { parent r }\n}\n";
    expectRoundTrip(deep);
}

TEST(ActorRoundTrip, AnglesInRadiansThatNoDegreesGiveAreWrittenInRadians)
{
    // From an AMC file in :RADIANS or the API: 0.7568359910159614 radians are no double number of degrees times
    // pi / 180, so they are written in radians; 1 radian is exactly 57.29577951308232 degrees.
    const std::string text = kActor.substr(0, kActor.size() - 3) +
                             "  dof rx min -1rad max 2.6663767342425704rad value 0.7568359910159614rad\n }\n" +
                             " clip c {\n  frame_rate 120\n  channels b.rz b.rx\n  frame 1.5945125561180293rad 90\n"
                             " }\n trajectory t { key 0 0 0 0 0.7927066908535559rad }\n}\n";
    expectRoundTrip(text);
    const ActorReadResult result = read(text);
    ASSERT_TRUE(result) << result.error;
    EXPECT_EQ(*result.document.joints[0].values[0], 0.7568359910159614);
    const std::string writtenText = written(result.document);
    EXPECT_NE(writtenText.find("dof rx min -57.29577951308232 max 2.6663767342425704rad value 0.7568359910159614rad"),
              std::string::npos)
        << writtenText;
    EXPECT_NE(writtenText.find("frame 1.5945125561180293rad 90"), std::string::npos) << writtenText;
    EXPECT_NE(writtenText.find("key 0 0 0 0 0.7927066908535559rad"), std::string::npos) << writtenText;
    EXPECT_EQ(readError(kActor + " trajectory t { key 0 0 0 0 radrad }\n}\n"),
              "t.actor:7: 'radrad': 'rad' is not a number");
}
