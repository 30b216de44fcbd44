// An imported glTF character as the target: Cesium Man (data/models/CesiumMan), whose joint names no built-in map
// knows, mapped by the topology guess, with CMU's 01_01.bvh retargeted onto it; and as the source: its walk, read as
// motion (readRiggedMotionFile), retargeted onto CMU's skeleton.
#include "RetargetTestUtil"

#include <osgActor/core/retarget/JointMapGuess>
#include <osgActor/core/retarget/RetargetMeasures>
#include <osgActor/import/RiggedActorBuilder>
#include <osgActor/import/RiggedModelFile>
#include <osgActor/import/RiggedMotionFile>

#include <glm/geometric.hpp>

#include <map>

using namespace osgActor;
using namespace osgActor::test;

namespace {

std::string cesiumManFile() { return std::string(OSGACTOR_TEST_DATA_DIR) + "/models/CesiumMan/CesiumMan.gltf"; }

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

/** CMU's 01_01.bvh and a rig retargeting it onto Cesium Man; rig is null (and the test failed) where either could
  * not be read or the rig not built. */
struct WalkOntoCesiumMan
{
    MocapImport walk;
    ActorDefinitionPtr cesium;
    RetargetRigPtr rig;
};

WalkOntoCesiumMan walkOntoCesiumMan()
{
    WalkOntoCesiumMan onto;
    onto.cesium = cesiumMan();
    if (!onto.cesium) return onto;
    onto.walk = readBvhScaled(assimpBvh("01_01.bvh"));
    onto.rig = buildRig(skeleton(onto.walk.definition), skeleton(onto.cesium));
    EXPECT_TRUE(onto.rig);
    return onto;
}

/** Cesium Man's walk read as motion and a rig retargeting it onto CMU's 12_03.bvh skeleton (in metres); rig is null
  * (and the test failed) where either could not be read or the rig not built. */
struct CesiumMansWalkOntoCmu
{
    MocapImport walk, cmu;
    RetargetRigPtr rig;
};

CesiumMansWalkOntoCmu cesiumMansWalkOntoCmu()
{
    CesiumMansWalkOntoCmu onto;
    onto.walk = readRiggedMotionFile(cesiumManFile(), MotionFileOptions());
    EXPECT_TRUE(onto.walk) << onto.walk.error;
    onto.cmu = readBvhScaled(repositoryMocap("bvh/12_03.bvh"), 0.056444);
    if (!onto.walk || !onto.cmu) return onto;
    onto.rig = buildRig(skeleton(onto.walk.definition), skeleton(onto.cmu.definition));
    EXPECT_TRUE(onto.rig);
    return onto;
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
    const WalkOntoCesiumMan onto = walkOntoCesiumMan();
    ASSERT_TRUE(onto.rig);
    const MocapImport& walk = onto.walk;
    const RetargetRigPtr& rig = onto.rig;
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

TEST(RetargetOntoGltf, EveryJointsSlideButTheRootsComesBackToRestWhateverTheFrameBrings)
{
    // The job's target values are in/out: slides moved away (a caller's own edits, another clip's frame) come back to
    // the rest pose's on the next frame, on all 18 of Cesium Man's sliding joints below the root, so bones keep their
    // lengths; the root's are placed where the source's root goes.
    const WalkOntoCesiumMan onto = walkOntoCesiumMan();
    ASSERT_TRUE(onto.rig);
    const MocapImport& walk = onto.walk;
    const ActorDefinitionPtr& cesium = onto.cesium;
    const RetargetRigPtr& rig = onto.rig;
    const std::vector<double>& rest = rig->getTargetRestDofs();
    std::vector<double> values = rest;
    unsigned moved = 0;
    for (unsigned j = 0; j < cesium->getNumJoints(); ++j)
        for (const int dof : cesium->getKinematics(j).translationDof)
            if (dof >= 0)
            {
                values[static_cast<unsigned>(dof)] += 0.25;
                ++moved;
            }
    EXPECT_GE(moved, 3u * 19u);
    RetargetWorkspace workspace;
    const unsigned frame = 100;
    RetargetJob job =
        retargetJob(*rig, Span<const double>(walk.clip->getFrame(frame), walk.clip->getNumChannels()), values, workspace);
    ASSERT_TRUE(job.run());
    const unsigned root = static_cast<unsigned>(rig->getTargetRoot());
    unsigned atRest = 0;
    for (unsigned j = 0; j < cesium->getNumJoints(); ++j)
        for (const int dof : cesium->getKinematics(j).translationDof)
        {
            if (dof < 0 || j == root) continue;
            EXPECT_EQ(values[static_cast<unsigned>(dof)], rest[static_cast<unsigned>(dof)])
                << cesium->getJointName(j) << " DOF " << dof;
            ++atRest;
        }
    EXPECT_GE(atRest, 3u * 18u);
    // The root sits where the source's goes (mapped), not 0.25 off it.
    const glm::dvec3 goal = rig->mapPosition(workspace.sourcePosition(static_cast<unsigned>(rig->getSourceRoot())));
    EXPECT_LE(glm::length(workspace.targetPosition(root) - goal), 1e-9);
}

TEST(RetargetOntoGltf, TheSourcesPoseReadBackIsItsOwnThoughTheFacingsDiffer)
{
    // Cesium Man faces another way than CMU's skeleton, so the rig's alignment A is a turn; the job keeps the source's
    // model matrices turned by A (folded into the root once), and what it gives back through sourceModel() and
    // sourcePosition() (what the IK pass and the measures read) is still the source's own forward kinematics; the
    // joints it places exactly take A * R_s(b) * postRotation (RetargetJointPlan), worked out here with GLM.
    const WalkOntoCesiumMan onto = walkOntoCesiumMan();
    ASSERT_TRUE(onto.rig);
    const RetargetRig& rig = *onto.rig;
    ASSERT_FALSE(rig.isAlignmentIdentity());
    const MocapImport& walk = onto.walk;
    const ActorDefinition& source = *walk.definition;
    const std::vector<std::uint8_t>& read = rig.getJobTables().sourceJointsRead;
    std::vector<double> values = rig.getTargetRestDofs();
    RetargetWorkspace workspace;
    unsigned exact = 0;
    for (unsigned f = 0; f < walk.clip->getNumFrames(); f += 250)
    {
        RetargetJob job =
            retargetJob(rig, Span<const double>(walk.clip->getFrame(f), walk.clip->getNumChannels()), values, workspace);
        ASSERT_TRUE(job.run());
        const std::vector<glm::dmat4> full = modelsAt(walk.definition, *walk.clip, f);
        for (unsigned j = 0; j < source.getNumJoints(); ++j)
        {
            const glm::dmat4 expected = read[j] ? full[j] : glm::dmat4(1.0);
            for (int c = 0; c < 4; ++c)
                for (int r = 0; r < 4; ++r)
                    EXPECT_NEAR(workspace.sourceModel(j)[c][r], expected[c][r], 1e-12) << source.getJointName(j);
            if (read[j])
            {
                EXPECT_LE(glm::length(workspace.sourcePosition(j) - glm::dvec3(full[j][3])), 1e-12);
            }
        }
        for (unsigned t = 0; t < rig.getTargetDefinition()->getNumJoints(); ++t)
        {
            const RetargetJointPlan& plan = rig.getPlan(t);
            if (!workspace.targetExact[t] || plan.weight != 1.0 || plan.sourceB < 0) continue;
            const glm::dmat3 desired = rig.getAlignment() * glm::dmat3(full[static_cast<unsigned>(plan.sourceB)]) *
                                       plan.postRotation;
            EXPECT_LE(angleBetween(workspace.targetRotation(t), desired), 1e-12);
            ++exact;
        }
    }
    EXPECT_GE(exact, 10u);
}

TEST(RetargetFromGltf, ReadingAModelAsMotionRefusesWhatItCannotRead)
{
    MotionFileOptions options;
    const MocapImport notAModel = readRiggedMotionFile(repositoryMocap("bvh/12_03.bvh"), options);
    EXPECT_FALSE(notAModel);
    EXPECT_NE(notAModel.error.find("12_03.bvh: not a rigged model file"), std::string::npos) << notAModel.error;

    options.animation = "run";
    const MocapImport unknown = readRiggedMotionFile(cesiumManFile(), options);
    EXPECT_FALSE(unknown);
    EXPECT_FALSE(unknown.clip);
    EXPECT_EQ(unknown.error, cesiumManFile() + ": no animation 'run' (the file has 'animation0')");

    options.animation.clear();
    options.scale = 0.01;
    const MocapImport scaled = readRiggedMotionFile(cesiumManFile(), options);
    EXPECT_FALSE(scaled);
    EXPECT_NE(scaled.error.find("scale 1"), std::string::npos) << scaled.error;
}

TEST(RetargetFromGltf, CesiumMansWalkReadAsMotionIsTheImportedActorsFirstClipNamedAsAsked)
{
    MotionFileOptions named;
    named.name = "walk";
    named.animation = "animation0";
    const MocapImport renamed = readAnyMotionFile(cesiumManFile(), named);
    ASSERT_TRUE(renamed) << renamed.error;
    EXPECT_EQ(renamed.clip->getName(), "walk");

    const MocapImport walk = readAnyMotionFile(cesiumManFile(), MotionFileOptions());
    ASSERT_TRUE(walk) << walk.error;
    ASSERT_TRUE(walk.clip);
    const ActorDefinitionPtr cesium = cesiumMan();
    ASSERT_TRUE(cesium);
    EXPECT_EQ(walk.clip->getName(), "animation0");
    EXPECT_EQ(walk.definition->getNumJoints(), cesium->getNumJoints());
    EXPECT_EQ(walk.clip->getNumChannels(), cesium->getNumDofs());
    // Standing Z up in metres: the head well above the feet, about Cesium Man's 1.2 m of joints.
    const std::vector<glm::dmat4> models = modelsAt(walk.definition, *walk.clip, 0);
    const unsigned head = static_cast<unsigned>(walk.definition->findJoint("Skeleton_neck_joint_2"));
    const unsigned ankle = static_cast<unsigned>(walk.definition->findJoint("leg_joint_L_3"));
    EXPECT_GT(models[head][3].z - models[ankle][3].z, 0.8);
    EXPECT_LT(models[head][3].z - models[ankle][3].z, 1.3);
}

TEST(RetargetFromGltf, CesiumMansWalkOntoCmusSkeletonKeepsBonesAndPutsFeetAndHandsWhereHisAre)
{
    const CesiumMansWalkOntoCmu onto = cesiumMansWalkOntoCmu();
    ASSERT_TRUE(onto.rig);
    const MocapImport& walk = onto.walk;
    const RetargetRigPtr& rig = onto.rig;
    RetargetClipOptions options;
    options.ik = true;
    const RetargetClipResult followed = retargetClip(*rig, *walk.clip, options);
    ASSERT_TRUE(followed) << followed.error;
    EXPECT_EQ(followed.numFrames, 61u); // 2 s at 30 frames per second, both ends
    const RetargetMeasures measures = measureRetargetedClip(*rig, *walk.clip, followed);
    EXPECT_LE(measures.largestLengthChange, 1e-9);
    ASSERT_EQ(measures.ends.size(), 4u);
    for (const RetargetMeasures::End& end : measures.ends)
        EXPECT_LE(end.largestError, 0.01 * measures.targetHeight) << end.limb;
    // He walks on the spot, so his feet slide back under him while down: no contact at the default speed. Found by
    // height alone (any speed), his steps are planted on the target, each still to within 1 cm on a 1.75 m body.
    EXPECT_TRUE(measures.contacts.empty());
    options.contacts.speed = 1e9;
    const RetargetClipResult planted = retargetClip(*rig, *walk.clip, options);
    ASSERT_TRUE(planted) << planted.error;
    const RetargetMeasures plantedMeasures = measureRetargetedClip(*rig, *walk.clip, planted);
    ASSERT_GE(plantedMeasures.contacts.size(), 2u);
    EXPECT_LE(plantedMeasures.largestSlip * 1.75 / plantedMeasures.targetHeight, 0.01);
    EXPECT_LE(plantedMeasures.largestLengthChange, 1e-9);
}

TEST(RetargetFromGltf, TheSourcesPoseIsItsForwardKinematicsWhereItsJointsSlideAndTheirOffsetsTurn)
{
    // Cesium Man's joints slide (translation DOFs on every joint) and their offsets turn, so the job's forward
    // kinematics builds their local matrices instead of only turning the parent's columns (RetargetSourceJoint::
    // turnsOnly): its model matrices are still the full forward kinematics' (1e-12, metres), on every tenth frame.
    const CesiumMansWalkOntoCmu onto = cesiumMansWalkOntoCmu();
    ASSERT_TRUE(onto.rig);
    const MocapImport& walk = onto.walk;
    const RetargetRigPtr& rig = onto.rig;
    const ActorDefinition& source = *walk.definition;
    const RetargetJobTables& tables = rig->getJobTables();
    unsigned built = 0;
    for (const RetargetSourceJoint& joint : tables.sourceJoints) built += joint.turnsOnly ? 0 : 1;
    EXPECT_GT(built, 10u) << "joints whose local matrix is built";
    std::vector<double> values = rig->getTargetRestDofs();
    RetargetWorkspace workspace;
    for (unsigned f = 0; f < walk.clip->getNumFrames(); f += 10)
    {
        RetargetJob job =
            retargetJob(*rig, Span<const double>(walk.clip->getFrame(f), walk.clip->getNumChannels()), values, workspace);
        ASSERT_TRUE(job.run());
        const std::vector<glm::dmat4> full = modelsAt(walk.definition, *walk.clip, f);
        for (unsigned j = 0; j < source.getNumJoints(); ++j)
        {
            if (!tables.sourceJointsRead[j]) continue;
            for (int c = 0; c < 4; ++c)
                for (int r = 0; r < 4; ++r)
                    EXPECT_NEAR(workspace.sourceModel(j)[c][r], full[j][c][r], 1e-12) << source.getJointName(j);
        }
    }
}
