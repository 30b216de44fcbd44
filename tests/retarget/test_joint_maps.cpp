// Joint maps: what resolveJointMap refuses (and says), the H-Anim table, the built-in maps against the real files,
// and the guess from names and from topology alone.
#include "RetargetTestUtil"

#include <osgActor/core/retarget/BuiltInJointMaps>
#include <osgActor/core/retarget/HAnimHumanoid>
#include <osgActor/core/retarget/JointMapGuess>

#include <map>
#include <set>

using namespace osgActor;
using namespace osgActor::test;

namespace {

/** A leg and an arm on a pelvis: enough joints to map, with known names. */
ActorDefinitionPtr smallBody()
{
    ActorDefinitionBuilder b("small");
    b.addJoint("pelvis").dofs(kRotationDofs);
    b.addJoint("thigh", "pelvis").offset(0.1, 0, -0.1).dofs(kRotationDofs);
    b.addJoint("shin", "thigh").offset(0, 0, -0.4).dofs(dofBit(Dof::RX));
    b.addJoint("chest", "pelvis").offset(0, 0, 0.4).dofs(kRotationDofs);
    b.addJoint("arm", "chest").offset(0.2, 0, 0.1).dofs(kRotationDofs);
    return b.build().definition;
}

std::string refusal(const JointMap& map, const ActorDefinition& definition)
{
    const JointMapResolveResult result = resolveJointMap(map, definition);
    EXPECT_FALSE(result) << "accepted map '" << map.getName() << "'";
    return result.error;
}

::testing::AssertionResult mentions(const std::string& text, const std::string& part)
{
    if (text.find(part) != std::string::npos) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << "'" << text << "' does not mention '" << part << "'";
}

/** joint name -> H-Anim name for every joint a resolved map names. */
std::map<std::string, std::string> namesOf(const JointMap& map, const ActorDefinition& definition)
{
    const JointMapResolveResult resolved = resolveJointMap(map, definition);
    EXPECT_TRUE(resolved) << resolved.error;
    std::map<std::string, std::string> names;
    for (unsigned j = 0; j < definition.getNumJoints(); ++j)
        if (resolved.map.hanimOfJoint[j] >= 0)
            names[definition.getJointName(j)] = getHAnimJoint(static_cast<unsigned>(resolved.map.hanimOfJoint[j])).name;
    return names;
}

} // namespace

TEST(JointMapResolve, RefusesAMapNamingAJointTheSkeletonLacksWithItsFileAndLine)
{
    JointMap map("mine");
    map.add("pelvis", "HumanoidRoot", "rig.map:1");
    map.add("femur", "l_hip", "rig.map:2");
    const std::string error = refusal(map, *smallBody());
    EXPECT_TRUE(mentions(error, "rig.map:2: joint map 'mine'")) << error;
    EXPECT_TRUE(mentions(error, "names joint 'femur', which the skeleton 'small' does not have"));
}

TEST(JointMapResolve, RefusesAliasesThatGoRoundInACycle)
{
    JointMap map("loop");
    map.add("thigh", "upper_leg", "loop.map:1");
    map.add("upper_leg", "leg_top", "loop.map:2");
    map.add("leg_top", "upper_leg", "loop.map:3");
    const std::string error = refusal(map, *smallBody());
    EXPECT_TRUE(
        mentions(error, "loop.map:1: joint map 'loop' has a cycle: thigh -> upper_leg -> leg_top -> upper_leg"));
}

TEST(JointMapResolve, RefusesANameThatLeadsToNoHAnimJoint)
{
    JointMap map;
    map.add("thigh", "left_thigh", "m:4");
    EXPECT_TRUE(mentions(refusal(map, *smallBody()),
                         "maps 'thigh' to 'left_thigh', which is neither an H-Anim joint name nor mapped itself"));
}

TEST(JointMapResolve, RefusesAMapThatContradictsTheHierarchy)
{
    // The shin lies below the thigh, but the map puts the knee above the hip: a cycle between the two trees.
    JointMap map;
    map.add("thigh", "l_knee");
    map.add("shin", "l_hip", "m:2");
    EXPECT_TRUE(mentions(refusal(map, *smallBody()),
                         "joint 'shin' (l_hip) lies below 'thigh' (l_knee), which H-Anim does not put above l_hip"));
    // Two joints of one H-Anim joint must be one line of descent, not siblings.
    JointMap siblings;
    siblings.add("thigh", "l_hip");
    siblings.add("chest", "l_hip", "m:7");
    EXPECT_TRUE(mentions(refusal(siblings, *smallBody()),
                         "joints 'thigh' and 'chest' both map to l_hip but neither lies below the other"));
}

TEST(JointMapResolve, DropsWhatContradictsTheHierarchyFromALooseMapInstead)
{
    JointMap map;
    map.setLooseMatching(true);
    map.add("THIGH", "l_knee");
    map.add("ns:shin", "l_hip");
    map.add("nowhere", "r_hip"); // loose maps may name joints the skeleton lacks
    const JointMapResolveResult resolved = resolveJointMap(map, *smallBody());
    ASSERT_TRUE(resolved) << resolved.error;
    ASSERT_EQ(resolved.map.dropped.size(), 1u);
    EXPECT_TRUE(mentions(resolved.map.dropped[0], "joint 'shin' (l_hip) lies below 'thigh'"));
    EXPECT_EQ(resolved.map.numMapped, 1u);
}

TEST(JointMapResolve, FollowsAliasesAndLetsATwistBoneShareItsBonesJoint)
{
    ActorDefinitionBuilder b("twist");
    b.addJoint("hips").dofs(kRotationDofs);
    b.addJoint("thigh", "hips").offset(0.1, 0, -0.1).dofs(kRotationDofs);
    b.addJoint("thigh_twist", "thigh").offset(0, 0, -0.2).dofs(dofBit(Dof::RZ));
    b.addJoint("shin", "thigh_twist").offset(0, 0, -0.2).dofs(dofBit(Dof::RX));
    const ActorDefinitionPtr definition = b.build().definition;
    JointMap map;
    map.add("hips", "HumanoidRoot");
    map.add("thigh", "upper_leg");
    map.add("upper_leg", "l_hip");
    map.add("thigh_twist", "l_hip");
    map.add("shin", "l_knee");
    const std::map<std::string, std::string> names = namesOf(map, *definition);
    EXPECT_EQ(names.at("thigh"), "l_hip");
    EXPECT_EQ(names.at("thigh_twist"), "l_hip");
    EXPECT_EQ(names.at("shin"), "l_knee");
}

TEST(HAnimHumanoid, LevelOneIsTheProjectsHumanoidAndParentsComeFirst)
{
    std::set<std::string> levelOne;
    for (unsigned i = 0; i < getNumHAnimJoints(); ++i)
    {
        const HAnimJoint& joint = getHAnimJoint(i);
        EXPECT_LT(joint.parent, static_cast<int>(i)) << joint.name;
        EXPECT_EQ(findHAnimJoint(joint.name), static_cast<int>(i));
        if (joint.levelOfArticulation <= 1) levelOne.insert(joint.name);
        EXPECT_EQ(mirrorHAnimJoint(mirrorHAnimJoint(static_cast<int>(i))), static_cast<int>(i));
    }
    EXPECT_EQ(getNumHAnimJoints(), 94u); // 24 vertebrae, 2 x 6 leg joints, 2 x 5 arm joints, 2 x 15 fingers, ...
    const ActorDefinitionPtr humanoid = readHumanoid();
    std::set<std::string> humanoidJoints;
    for (unsigned j = 0; j < humanoid->getNumJoints(); ++j) humanoidJoints.insert(humanoid->getJointName(j));
    EXPECT_EQ(levelOne, humanoidJoints);
    EXPECT_TRUE(isHAnimAncestor(findHAnimJoint("vt1"), findHAnimJoint("l_wrist")));
    EXPECT_FALSE(isHAnimAncestor(findHAnimJoint("l_wrist"), findHAnimJoint("vt1")));
    EXPECT_EQ(getHAnimJoint(static_cast<unsigned>(mirrorHAnimJoint(findHAnimJoint("l_index2")))).name,
              std::string("r_index2"));
    EXPECT_EQ(mirrorHAnimJoint(findHAnimJoint("skullbase")), findHAnimJoint("skullbase"));
}

TEST(BuiltInJointMaps, FitTheirRealFilesWithoutContradiction)
{
    struct Case
    {
        MocapImport file;
        JointMapStyle style;
        std::map<std::string, std::string> expected;
    };
    const std::vector<Case> cases = {
        {readCmuAmc("11.asf", "11_01.amc"),
         JointMapStyle::CmuAsf,
         {{"root", "HumanoidRoot"}, {"lfemur", "l_hip"}, {"rtibia", "r_knee"}, {"lfoot", "l_ankle"},
          {"lclavicle", "l_sternoclavicular"}, {"lhumerus", "l_shoulder"}, {"rradius", "r_elbow"},
          {"lwrist", "l_wrist"}, {"lhand", "l_wrist"}, {"head", "skullbase"}}},
        {readCmuAmc("charleston.asf", "charleston1.amc"), JointMapStyle::CmuAsf, {{"rhumerus", "r_shoulder"}}},
        {readBvhScaled(repositoryMocap("bvh/12_03.bvh")),
         JointMapStyle::CmuBvh,
         {{"Hips", "HumanoidRoot"}, {"LeftUpLeg", "l_hip"}, {"RightLeg", "r_knee"},
          {"LeftShoulder", "l_sternoclavicular"}, {"LeftArm", "l_shoulder"}, {"RightForeArm", "r_elbow"},
          {"LeftHand", "l_wrist"}, {"LeftFingerBase", "l_wrist"}, {"Head", "skullbase"}}},
        {readBvhScaled(assimpBvh("01_01.bvh")), JointMapStyle::CmuBvh, {{"LFingers", "l_index1"}}},
        {readBvhScaled(assimpBvh("01_03.bvh")), JointMapStyle::CmuBvh, {{"RThumb", "r_thumb1"}}},
        {readBvhScaled(assimpBvh("Boxing_Toes.bvh")),
         JointMapStyle::MotionBuilderBvh,
         {{"Hips", "HumanoidRoot"}, {"LeftHip", "l_hip"}, {"RightKnee", "r_knee"}, {"LeftCollar", "l_sternoclavicular"},
          {"LeftShoulder", "l_shoulder"}, {"RightElbow", "r_elbow"}, {"LeftWrist", "l_wrist"},
          {"LeftToes", "l_metatarsal"}, {"Chest", "vt6"}}},
        {readBvhScaled(repositoryMocap("bvh/tpose.bvh"), 0.1, UpAxis::Z),
         JointMapStyle::MakeHuman,
         {{"root", "HumanoidRoot"}, {"upperleg01.L", "l_hip"}, {"upperleg02.L", "l_hip"}, {"lowerleg02.R", "r_knee"},
          {"clavicle.L", "l_sternoclavicular"}, {"upperarm02.R", "r_shoulder"}, {"wrist.L", "l_wrist"},
          {"finger1-1.L", "l_thumb1"}, {"finger2-3.R", "r_index3"}, {"spine05", "vl5"}, {"head", "skullbase"}}},
    };
    for (const Case& c : cases)
    {
        SCOPED_TRACE(c.file.definition->getName());
        const JointMap& map = builtInJointMap(c.style);
        const JointMapResolveResult resolved = resolveJointMap(map, *c.file.definition);
        ASSERT_TRUE(resolved) << resolved.error;
        EXPECT_TRUE(resolved.map.dropped.empty()) << resolved.map.dropped.front();
        const std::map<std::string, std::string> names = namesOf(map, *c.file.definition);
        for (const auto& pair : c.expected)
        {
            ASSERT_TRUE(names.count(pair.first)) << pair.first;
            EXPECT_EQ(names.at(pair.first), pair.second) << pair.first;
        }
        // The guess picks this map.
        const JointMapGuess guess = guessJointMap(*c.file.definition);
        EXPECT_EQ(guess.method, std::string("built-in map '") + jointMapStyleName(c.style) + "'");
    }
}

TEST(BuiltInJointMaps, MixamoNamesWithAnyNamespaceAndTheHumanoidsOwnNames)
{
    // No Mixamo file is in the repository or in Debian's test models: a skeleton with Mixamo's names stands in.
    ActorDefinitionBuilder b("mixamo");
    auto add = [&b](const std::string& name, const std::string& parent, double x, double y, double z) {
        b.addJoint("mixamorig1:" + name, parent.empty() ? "" : "mixamorig1:" + parent)
            .offset(x, y, z)
            .dofs(kRotationDofs);
    };
    add("Hips", "", 0, 0, 1);
    add("Spine", "Hips", 0, 0, 0.1);
    add("Spine1", "Spine", 0, 0, 0.12);
    add("Spine2", "Spine1", 0, 0, 0.14);
    add("Neck", "Spine2", 0, 0, 0.15);
    add("Head", "Neck", 0, 0, 0.1);
    for (const char* side : {"Left", "Right"})
    {
        const double x = std::string(side) == "Left" ? 1.0 : -1.0;
        const std::string s = side;
        add(s + "Shoulder", "Spine2", 0.05 * x, 0, 0.1);
        add(s + "Arm", s + "Shoulder", 0.1 * x, 0, 0);
        add(s + "ForeArm", s + "Arm", 0.28 * x, 0, 0);
        add(s + "Hand", s + "ForeArm", 0.25 * x, 0, 0);
        add(s + "HandIndex1", s + "Hand", 0.08 * x, 0, 0);
        add(s + "UpLeg", "Hips", 0.09 * x, 0, -0.05);
        add(s + "Leg", s + "UpLeg", 0, 0, -0.42);
        add(s + "Foot", s + "Leg", 0, 0, -0.42);
        add(s + "ToeBase", s + "Foot", 0, -0.12, -0.06);
    }
    const ActorDefinitionPtr mixamo = b.build().definition;
    ASSERT_TRUE(mixamo);
    const std::map<std::string, std::string> names = namesOf(builtInJointMap(JointMapStyle::Mixamo), *mixamo);
    EXPECT_EQ(names.at("mixamorig1:Hips"), "HumanoidRoot");
    EXPECT_EQ(names.at("mixamorig1:LeftShoulder"), "l_sternoclavicular");
    EXPECT_EQ(names.at("mixamorig1:LeftArm"), "l_shoulder");
    EXPECT_EQ(names.at("mixamorig1:RightHandIndex1"), "r_index1");
    EXPECT_EQ(names.at("mixamorig1:Spine2"), "vt6");
    EXPECT_EQ(guessJointMap(*mixamo).method, "built-in map 'mixamo'");

    const ActorDefinitionPtr humanoid = readHumanoid();
    const JointMapGuess guess = guessJointMap(*humanoid);
    EXPECT_EQ(guess.method, "built-in map 'hanim'");
    EXPECT_TRUE(guess.missingHAnim.empty());
    EXPECT_EQ(guess.map.getEntries().size(), humanoid->getNumJoints());
}

TEST(JointMapGuess, FindsTheBodyByTopologyAloneOnEveryRealSkeleton)
{
    // Each real skeleton with its names taken away: the topology guess must find the level-1 joints the built-in map
    // finds by name (twist bones, clavicles and spine ends aside, which the built-in maps name more finely).
    const char* const kCompared[] = {"HumanoidRoot", "l_hip",      "r_hip",      "l_knee",  "r_knee",
                                     "l_ankle",      "r_ankle",    "l_shoulder", "r_shoulder", "l_elbow",
                                     "r_elbow",      "skullbase"};
    const std::vector<MocapImport> files = {
        readCmuAmc("11.asf", "11_01.amc"), readBvhScaled(repositoryMocap("bvh/12_03.bvh")),
        readBvhScaled(assimpBvh("01_01.bvh")), readBvhScaled(assimpBvh("Boxing_Toes.bvh")),
        readBvhScaled(repositoryMocap("bvh/tpose.bvh"), 0.1, UpAxis::Z)};
    std::vector<ActorDefinitionPtr> skeletons;
    for (const MocapImport& file : files) skeletons.push_back(file.definition);
    skeletons.push_back(readHumanoid());
    for (const ActorDefinitionPtr& named : skeletons)
    {
        SCOPED_TRACE(named->getName());
        const JointMapGuess byName = guessJointMap(*named);
        const ActorDefinitionPtr unnamed = withoutNames(*named);
        const JointMapGuess byShape = guessJointMap(*unnamed);
        EXPECT_EQ(byShape.method, "topology");
        const std::map<std::string, std::string> nameMap = namesOf(byName.map, *named);
        const std::map<std::string, std::string> shapeMap = namesOf(byShape.map, *unnamed);
        for (const char* hanim : kCompared)
        {
            std::string expected, found;
            for (const auto& pair : nameMap)
                if (pair.second == hanim && expected.empty())
                    expected = "j" + std::to_string(named->findJoint(pair.first));
            for (const auto& pair : shapeMap)
                if (pair.second == hanim && (found.empty() || unnamed->findJoint(pair.first) <
                                                                  unnamed->findJoint(found)))
                    found = pair.first;
            EXPECT_EQ(found, expected) << hanim;
        }
    }
}

TEST(JointMapGuess, SaysWhatItCouldNotMap)
{
    // A chain with no legs: no topology, no names.
    ActorDefinitionBuilder b("snake");
    b.addJoint("a").dofs(kRotationDofs);
    b.addJoint("b", "a").offset(0, 0.3, 0).dofs(kRotationDofs);
    b.addJoint("c", "b").offset(0, 0.3, 0).dofs(kRotationDofs);
    const JointMapGuess guess = guessJointMap(*b.build().definition);
    EXPECT_TRUE(guess.map.empty());
    EXPECT_EQ(guess.missingHAnim.size(), 18u);
    EXPECT_EQ(guess.unmappedJoints, (std::vector<std::string>{"a", "b", "c"}));
    ASSERT_FALSE(guess.notes.empty());
    EXPECT_TRUE(mentions(describeJointMapGuess(guess), "H-Anim level-1 joints not found: HumanoidRoot"));
}
