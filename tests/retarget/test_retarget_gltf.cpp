// An imported glTF character as the target: Cesium Man (data/models/CesiumMan), whose joint names no built-in map
// knows, mapped by the topology guess, with CMU's 01_01.bvh retargeted onto it.
#include "RetargetTestUtil"

#include <osgActor/core/retarget/JointMapGuess>
#include <osgActor/core/retarget/RetargetMeasures>
#include <osgActor/import/RiggedActorBuilder>
#include <osgActor/import/RiggedModelFile>

#include <map>

using namespace osgActor;
using namespace osgActor::test;

namespace {

/** Cesium Man as an actor standing Z up, in metres (its root scale in the lengths). */
ActorDefinitionPtr cesiumMan()
{
    const RiggedModelRead read =
        readRiggedModelFile(std::string(OSGACTOR_TEST_DATA_DIR) + "/models/CesiumMan/CesiumMan.gltf");
    EXPECT_TRUE(read) << read.error;
    if (!read) return nullptr;
    RiggedActorOptions options;
    options.rootScale = RootScale::InLengths;
    options.zUp = true;
    const RiggedActor actor = buildRiggedActor(read.model, options);
    EXPECT_TRUE(actor) << actor.error;
    return actor.definition;
}

} // namespace

TEST(RetargetOntoGltf, TheGuessFindsCesiumMansBodyByItsShape)
{
    const ActorDefinitionPtr cesium = cesiumMan();
    ASSERT_TRUE(cesium);
    const JointMapGuess guess = guessJointMap(*cesium);
    EXPECT_EQ(guess.method, "topology");
    std::map<std::string, std::string> names;
    for (const JointMapEntry& entry : guess.map.getEntries()) names[entry.joint] = entry.hanim;
    // Its legs go hip, knee, ankle, toe (leg_joint_L_1, _2, _3, _5); its arms hang in an A-pose.
    EXPECT_EQ(names["Skeleton_torso_joint_1"], "HumanoidRoot");
    EXPECT_EQ(names["leg_joint_L_1"], "l_hip");
    EXPECT_EQ(names["leg_joint_L_2"], "l_knee");
    EXPECT_EQ(names["leg_joint_L_3"], "l_ankle");
    EXPECT_EQ(names["leg_joint_R_3"], "r_ankle");
    EXPECT_EQ(names["Skeleton_arm_joint_L__4_"], "l_shoulder");
    EXPECT_EQ(names["Skeleton_arm_joint_L__3_"], "l_elbow");
    EXPECT_EQ(names["Skeleton_arm_joint_R__3_"], "r_wrist");
    EXPECT_EQ(names["Skeleton_neck_joint_2"], "skullbase");
    EXPECT_EQ(guess.missingHAnim, (std::vector<std::string>{"sacroiliac", "l_midtarsal", "r_midtarsal"}));
}

TEST(RetargetOntoGltf, CmuWalksOntoCesiumManKeepFeetPlantedAndEndsInPlace)
{
    const ActorDefinitionPtr cesium = cesiumMan();
    ASSERT_TRUE(cesium);
    const MocapImport walk = readBvhScaled(assimpBvh("01_01.bvh"));
    const RetargetRigPtr rig = buildRig(skeleton(walk.definition), skeleton(cesium));
    ASSERT_TRUE(rig);
    RetargetClipOptions options;
    options.ik = true;
    const RetargetClipResult planted = retargetClip(*rig, *walk.clip, options);
    ASSERT_TRUE(planted) << planted.error;
    const RetargetMeasures measures = measureRetargetedClip(*rig, *walk.clip, planted);
    const double toHeight = 1.75 / measures.targetHeight;
    ASSERT_GE(measures.contacts.size(), 4u);
    EXPECT_LE(measures.largestSlip * toHeight, 0.01);
    ASSERT_EQ(measures.ends.size(), 4u);
    for (const RetargetMeasures::End& end : measures.ends)
        EXPECT_LE(end.largestError, 0.01 * measures.targetHeight) << end.limb;
    // Every joint of Cesium Man slides (tx, ty, tz): only the root's move, so its bones keep their lengths.
    EXPECT_LE(measures.largestLengthChange, 1e-9);
}
