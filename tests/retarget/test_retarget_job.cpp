// The per-frame retargeting: what validate() refuses, then the measures of issue 27 on real motion capture: the same
// skeleton reproduces its DOFs, T-pose and A-pose targets move alike, bones keep their lengths, bones along other
// local axes move alike; and by hand: a spine of 3 onto a spine of 5, slides of every layout back to rest, a hinge at
// its limit.
#include "RetargetTestUtil"

#include <osgActor/core/retarget/JointRotationFit>
#include <osgActor/core/retarget/RetargetMeasures>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>

#include <limits>
#include <random>

using namespace osgActor;
using namespace osgActor::test;

namespace {

/** Retargets a whole clip without the IK pass, failing the test on an error. */
RetargetClipResult retargetAll(const RetargetRigPtr& rig, const Clip& clip)
{
    const RetargetClipResult result = retargetClip(*rig, clip);
    EXPECT_TRUE(result) << result.error;
    return result;
}

/** A chain skeleton: root (6 DOFs) and n spine joints of length `length` each along +Z, then a head. */
ActorDefinitionPtr spine(const std::string& name, unsigned n, double length)
{
    ActorDefinitionBuilder b(name);
    b.addJoint("root").offset(0, 0, 1).dofs(kRotationDofs | Dof::TX | Dof::TY | Dof::TZ);
    std::string parent = "root";
    for (unsigned i = 0; i < n; ++i)
    {
        const std::string joint = "s" + std::to_string(i);
        b.addJoint(joint, parent).offset(0, 0, i == 0 ? 0.0 : length).dofs(kRotationDofs);
        parent = joint;
    }
    b.addJoint("head", parent).offset(0, 0, length).dofs(kRotationDofs);
    b.addJoint("head_end", "head").offset(0, 0, 0.2);
    return b.build().definition;
}

/** Target joint t's desired model rotation for the frame in the workspace (RetargetJointPlan's formula, worked out
  * with GLM): A * R_s(b) * postRotation, or A * slerp(changes since rest of a and b) * postRotation. */
glm::dmat3 desiredRotation(const RetargetRig& rig, const RetargetWorkspace& w, unsigned t)
{
    const auto change = [&](int joint) {
        if (joint < 0) return glm::dquat(1.0, 0.0, 0.0, 0.0);
        const unsigned j = static_cast<unsigned>(joint);
        return glm::quat_cast(w.sourceRotation(j) * glm::transpose(glm::dmat3(rig.getSourceRestModels()[j])));
    };
    const RetargetJointPlan& plan = rig.getPlan(t);
    if (plan.weight == 1.0)
        return rig.getAlignment() * w.sourceRotation(static_cast<unsigned>(plan.sourceB)) * plan.postRotation;
    return rig.getAlignment() * glm::mat3_cast(glm::slerp(change(plan.sourceA), change(plan.sourceB), plan.weight)) *
           plan.postRotation;
}

/** Runs the job on every frame of clip; on every tenth, checks that each joint flagged in `batched` takes the angles
  * fitJointRotationDofs gives for its desired model rotation under its parent's actual one, the previous frame's
  * values as the reference. Returns how many joints it compared. */
unsigned compareBatchedWithScalarFits(const RetargetRig& rig, const Clip& clip, const std::vector<std::uint8_t>& batched)
{
    const ActorDefinition& target = *rig.getTargetDefinition();
    RetargetWorkspace workspace;
    std::vector<double> values = rig.getTargetRestDofs();
    unsigned compared = 0;
    for (unsigned f = 0; f < clip.getNumFrames(); ++f)
    {
        const std::vector<double> previous = values;
        RetargetJob job =
            retargetJob(rig, Span<const double>(clip.getFrame(f), clip.getNumChannels()), values, workspace);
        EXPECT_TRUE(job.run());
        if (f % 10 != 0) continue;
        for (unsigned t = 0; t < target.getNumJoints(); ++t)
        {
            if (!batched[t]) continue;
            const int parent = target.getParent(t);
            const glm::dmat3 parentRotation =
                parent >= 0 ? workspace.targetRotation(static_cast<unsigned>(parent)) : glm::dmat3(1.0);
            const glm::dmat3 frame = parentRotation * rig.getTargetOffsetRotations()[t];
            std::vector<double> expected = previous;
            fitJointRotationDofs(target, t, glm::transpose(frame) * desiredRotation(rig, workspace, t),
                                 expected.data());
            const JointKinematics& k = target.getKinematics(t);
            for (unsigned r = 0; r < k.numRotations; ++r)
                EXPECT_NEAR(values[k.rotationDof[r]], expected[k.rotationDof[r]], 1e-12)
                    << target.getJointName(t) << " frame " << f;
            ++compared;
        }
    }
    return compared;
}

} // namespace

TEST(RetargetJob, RefusesWrongSizesAndValuesThatAreNotFinite)
{
    const ActorDefinitionPtr humanoid = readHumanoid();
    const RetargetRigPtr rig = buildRig(skeleton(humanoid), skeleton(humanoid));
    ASSERT_TRUE(rig);
    RetargetWorkspace workspace;
    std::vector<double> source = humanoid->getDefaultDofs(), target = humanoid->getDefaultDofs();
    RetargetJob job;
    job.rig = rig.get();
    job.sourceDofs = source;
    job.targetDofs = target;
    job.workspace = &workspace;
    EXPECT_FALSE(job.validate()) << "a workspace not sized for the rig";
    workspace.resize(*rig);
    EXPECT_TRUE(job.validate());
    job.sourceDofs = Span<const double>(source.data(), source.size() - 1);
    EXPECT_FALSE(job.run());
    job.sourceDofs = source;
    source[3] = std::numeric_limits<double>::quiet_NaN();
    const std::vector<double> before = target;
    EXPECT_FALSE(job.run());
    EXPECT_EQ(target, before) << "nothing written";
    source[3] = 2e150;
    EXPECT_FALSE(job.run());
    source[3] = 0.0;
    // A value that is not finite anywhere in the target's DOFs: first, in the vectors the check reads eight at a time,
    // and last (the DOFs past the last whole vector).
    for (const std::size_t dof : {std::size_t(0), std::size_t(5), std::size_t(9), target.size() - 1})
        for (const double bad : {std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
                                 std::numeric_limits<double>::quiet_NaN()})
        {
            const double kept = target[dof];
            target[dof] = bad;
            EXPECT_FALSE(job.run()) << "target DOF " << dof << " = " << bad;
            target[dof] = kept;
        }
    EXPECT_TRUE(job.run());
    job.rig = nullptr;
    EXPECT_FALSE(job.run());
}

TEST(RetargetJob, TheSameSkeletonReproducesItsDofs)
{
    // Both CMU formats, BVH and ASF/AMC, every frame; and the humanoid, whose DOFs have limits, on a random pose.
    for (const MocapImport& motion :
         {readBvhScaled(repositoryMocap("bvh/12_03.bvh")), readCmuAmc("charleston.asf", "charleston1.amc")})
    {
        SCOPED_TRACE(motion.definition->getName());
        const RetargetRigPtr rig = buildRig(skeleton(motion.definition), skeleton(motion.definition));
        ASSERT_TRUE(rig);
        const RetargetClipResult result = retargetAll(rig, *motion.clip);
        ASSERT_EQ(result.clip->getNumFrames(), motion.clip->getNumFrames());
        double largest = 0.0;
        for (unsigned f = 0; f < motion.clip->getNumFrames(); ++f)
            for (unsigned d = 0; d < motion.clip->getNumChannels(); ++d)
                largest = std::max(largest, std::abs(result.clip->getFrame(f)[d] - motion.clip->getFrame(f)[d]));
        EXPECT_LE(largest, 1e-9);
    }
    const ActorDefinitionPtr humanoid = readHumanoid();
    const RetargetRigPtr rig = buildRig(skeleton(humanoid), skeleton(humanoid));
    std::mt19937 random(27);
    std::vector<double> pose(humanoid->getNumDofs());
    for (unsigned d = 0; d < pose.size(); ++d)
    {
        const double lo = std::max(humanoid->getDofMin(d), -1.0), hi = std::min(humanoid->getDofMax(d), 1.0);
        pose[d] = std::uniform_real_distribution<double>(lo, hi)(random);
    }
    RetargetWorkspace workspace;
    std::vector<double> target = humanoid->getDefaultDofs();
    RetargetJob job = retargetJob(*rig, pose, target, workspace);
    ASSERT_TRUE(job.run());
    for (unsigned d = 0; d < pose.size(); ++d) EXPECT_NEAR(target[d], pose[d], 1e-9) << humanoid->getDofName(d);
    EXPECT_EQ(job.numInexact, 0u);
}

TEST(RetargetJob, TPoseAndAPoseTargetsTurnTheirJointsAlike)
{
    // The same target skeleton with its rest pose's arms out (T) or half down (A): the retargeting reconciles each
    // with the source's rest pose, so every joint's world orientation agrees on every frame.
    const MocapImport walk = readBvhScaled(repositoryMocap("bvh/12_03.bvh"));
    struct Variant
    {
        ActorDefinitionPtr definition;
        std::vector<double> tPose, aPose;
    };
    const ActorDefinitionPtr humanoid = readHumanoid();
    const MocapImport boxing = readBvhScaled(assimpBvh("Boxing_Toes.bvh"), 0.01);
    const std::vector<Variant> variants = {
        {humanoid, restWith(*humanoid, {{"l_shoulder.ry", degrees(-90)}, {"r_shoulder.ry", degrees(90)}}),
         restWith(*humanoid, {{"l_shoulder.ry", degrees(-45)}, {"r_shoulder.ry", degrees(45)}})},
        {boxing.definition, boxing.definition->getDefaultDofs(),
         restWith(*boxing.definition, {{"LeftShoulder.rz", degrees(-45)}, {"RightShoulder.rz", degrees(45)}})}};
    for (const Variant& variant : variants)
    {
        SCOPED_TRACE(variant.definition->getName());
        const RetargetRigPtr tRig = buildRig(skeleton(walk.definition), skeleton(variant.definition, variant.tPose));
        const RetargetRigPtr aRig = buildRig(skeleton(walk.definition), skeleton(variant.definition, variant.aPose));
        ASSERT_TRUE(tRig && aRig);
        const RetargetClipResult t = retargetAll(tRig, *walk.clip), a = retargetAll(aRig, *walk.clip);
        double largest = 0.0;
        for (unsigned f = 0; f < t.numFrames; ++f)
        {
            const std::vector<glm::dmat4> tModels = modelsAt(variant.definition, *t.clip, f);
            const std::vector<glm::dmat4> aModels = modelsAt(variant.definition, *a.clip, f);
            for (unsigned j = 0; j < tModels.size(); ++j)
                largest = std::max(largest, angleBetween(glm::dmat3(tModels[j]), glm::dmat3(aModels[j])));
        }
        EXPECT_LE(largest, degrees(0.5));
    }
}

TEST(RetargetJob, EveryTargetBoneKeepsItsLengthOnEveryFrame)
{
    const MocapImport walk = readBvhScaled(assimpBvh("01_01.bvh"));
    const MocapImport boxing = readBvhScaled(assimpBvh("Boxing_Toes.bvh"), 0.01);
    for (const ActorDefinitionPtr& target : {readHumanoid(), boxing.definition})
    {
        SCOPED_TRACE(target->getName());
        const RetargetRigPtr rig = buildRig(skeleton(walk.definition), skeleton(target));
        const RetargetClipResult result = retargetAll(rig, *walk.clip);
        const RetargetMeasures measures = measureRetargetedClip(*rig, *walk.clip, result);
        EXPECT_LE(measures.largestLengthChange, 1e-9);
        EXPECT_GT(measures.targetHeight, 1.5);
    }
}

TEST(RetargetJob, BonesAlongOtherLocalAxesMoveAlike)
{
    // Boxing_Toes.bvh, and the same skeleton with every joint's frame turned by a rotation of its own (its children's
    // offsets turned back, so the rest geometry is the same): the retargeted joints go to the same places.
    const MocapImport walk = readBvhScaled(repositoryMocap("bvh/12_03.bvh"));
    const ActorDefinitionPtr boxing = readBvhScaled(assimpBvh("Boxing_Toes.bvh"), 0.01).definition;
    ActorDefinitionBuilder builder = toBuilder(*boxing);
    std::mt19937 random(5);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    std::vector<glm::dquat> turn(builder.getNumJoints());
    for (glm::dquat& q : turn) q = glm::normalize(glm::dquat(unit(random), unit(random), unit(random), unit(random)));
    for (unsigned j = 0; j < builder.getNumJoints(); ++j)
    {
        JointSpec& spec = builder.joint(j).spec();
        const int parent = boxing->getParent(j);
        const glm::dquat parentTurn = parent >= 0 ? turn[static_cast<unsigned>(parent)] : glm::dquat(1, 0, 0, 0);
        spec.translation = glm::inverse(parentTurn) * spec.translation;
        spec.rotation = glm::inverse(parentTurn) * spec.rotation * turn[j];
    }
    const ActorDefinitionPtr turned = builder.build().definition;
    ASSERT_TRUE(turned);
    const RetargetRigPtr plain = buildRig(skeleton(walk.definition), skeleton(boxing));
    const RetargetRigPtr other = buildRig(skeleton(walk.definition), skeleton(turned));
    const RetargetClipResult a = retargetAll(plain, *walk.clip), b = retargetAll(other, *walk.clip);
    double largest = 0.0;
    for (unsigned f = 0; f < a.numFrames; f += 5)
    {
        const std::vector<glm::dmat4> aModels = modelsAt(boxing, *a.clip, f), bModels = modelsAt(turned, *b.clip, f);
        for (unsigned j = 0; j < aModels.size(); ++j)
            largest = std::max(largest, glm::length(glm::dvec3(aModels[j][3]) - glm::dvec3(bModels[j][3])));
    }
    EXPECT_LE(largest, 1e-9);
}

TEST(RetargetJob, ASpineOfThreeOntoASpineOfFiveSharesTheBendOut)
{
    // Each of the source's three spine joints bends 10 degrees about X: the target's five, unpaired between the first
    // and the head, bend 6 degrees each (the bend spread along the chain), and the head ends where the source's does.
    const ActorDefinitionPtr three = spine("three", 3, 0.2), five = spine("five", 5, 0.12);
    const std::vector<std::pair<std::string, std::string>> ends = {
        {"root", "HumanoidRoot"}, {"s0", "vl5"}, {"head", "skullbase"}};
    const RetargetRigPtr rig = buildRig(mappedSkeleton(three, ends), mappedSkeleton(five, ends));
    ASSERT_TRUE(rig);
    std::vector<double> bent = three->getDefaultDofs();
    for (const char* joint : {"s0.rx", "s1.rx", "s2.rx"})
        bent[static_cast<unsigned>(three->findDof(joint))] = degrees(10);
    RetargetWorkspace workspace;
    std::vector<double> result = five->getDefaultDofs();
    RetargetJob job = retargetJob(*rig, bent, result, workspace);
    ASSERT_TRUE(job.run());
    for (unsigned i = 0; i < 5; ++i)
    {
        const std::string joint = "s" + std::to_string(i);
        EXPECT_NEAR(result[static_cast<unsigned>(five->findDof(joint + ".rx"))], degrees(6), 1e-9) << joint;
        EXPECT_NEAR(result[static_cast<unsigned>(five->findDof(joint + ".ry"))], 0.0, 1e-12) << joint;
    }
    const unsigned sourceHead = static_cast<unsigned>(three->findJoint("head"));
    const unsigned targetHead = static_cast<unsigned>(five->findJoint("head"));
    EXPECT_LE(angleBetween(workspace.sourceRotation(sourceHead), workspace.targetRotation(targetHead)), 1e-12);
}

TEST(RetargetJob, ASourceOfFewerThanFourDofsIsPosedAndReproduced)
{
    // The job takes the source's sines and cosines four consecutive DOFs at a time; a source of two DOFs (an arm
    // turning about X and Y under a root without DOFs) has fewer than a column of them. Onto itself, its DOFs come back
    // (1e-9) and its pose is its forward kinematics (1e-12).
    ActorDefinitionBuilder b("arm");
    b.addJoint("root").offset(0, 0, 1);
    b.addJoint("arm", "root").offset(0, 0.1, 0.5).dofs(Dof::RX | Dof::RY);
    b.addJoint("hand", "arm").offset(0, 0, 0.3);
    const ActorDefinitionPtr arm = b.build().definition;
    ASSERT_TRUE(arm);
    ASSERT_EQ(arm->getNumDofs(), 2u);
    const std::vector<std::pair<std::string, std::string>> names = {
        {"root", "HumanoidRoot"}, {"arm", "l_shoulder"}, {"hand", "l_elbow"}};
    const RetargetRigPtr rig = buildRig(mappedSkeleton(arm, names), mappedSkeleton(arm, names));
    ASSERT_TRUE(rig);
    RetargetWorkspace workspace;
    std::vector<double> result = arm->getDefaultDofs();
    for (const std::vector<double>& pose : {std::vector<double>{degrees(30), degrees(-50)},
                                            std::vector<double>{degrees(-120), degrees(10)}})
    {
        RetargetJob job = retargetJob(*rig, pose, result, workspace);
        ASSERT_TRUE(job.run());
        EXPECT_NEAR(result[0], pose[0], 1e-9);
        EXPECT_NEAR(result[1], pose[1], 1e-9);
        ActorPose posed(arm);
        posed.setDofs(pose.data(), pose.size());
        posed.updateMatrices();
        for (unsigned j = 0; j < arm->getNumJoints(); ++j)
            for (int c = 0; c < 4; ++c)
                for (int r = 0; r < 4; ++r)
                    EXPECT_NEAR(workspace.sourceModel(j)[c][r], posed.getModelMatrix(j)[c][r], 1e-12)
                        << arm->getJointName(j);
    }
}

TEST(RetargetJob, ASkeletonWithoutRotationsOntoItselfTakesItsTravel)
{
    // No joint turns, so the job has no batch of angles at all (no Euler, copy or axis lane): its joints are placed
    // from the rest of their plans, and the root's slides carry the source's travel.
    ActorDefinitionBuilder b("slider");
    b.addJoint("root").offset(0, 0, 1).dofs(Dof::TX | Dof::TY | Dof::TZ);
    b.addJoint("arm", "root").offset(0, 0.1, 0.5);
    b.addJoint("hand", "arm").offset(0, 0, 0.3);
    const ActorDefinitionPtr slider = b.build().definition;
    ASSERT_TRUE(slider);
    const std::vector<std::pair<std::string, std::string>> names = {
        {"root", "HumanoidRoot"}, {"arm", "l_shoulder"}, {"hand", "l_elbow"}};
    const RetargetRigPtr rig = buildRig(mappedSkeleton(slider, names), mappedSkeleton(slider, names));
    ASSERT_TRUE(rig);
    EXPECT_TRUE(rig->getJobTables().eulerBatches.empty());
    EXPECT_TRUE(rig->getJobTables().copyBatches.empty());
    EXPECT_EQ(rig->getJobTables().placement[static_cast<unsigned>(slider->findJoint("arm"))], RetargetPlacement::Copy);
    RetargetWorkspace workspace;
    std::vector<double> result = slider->getDefaultDofs();
    const std::vector<double> moved = {0.3, -0.2, 0.1};
    RetargetJob job = retargetJob(*rig, moved, result, workspace);
    ASSERT_TRUE(job.run());
    for (unsigned d = 0; d < 3; ++d) EXPECT_NEAR(result[d], moved[d], 1e-12) << d;
    EXPECT_EQ(job.numInexact, 0u);
}

TEST(RetargetJob, SlidesOfEveryLayoutComeBackToRestInOneFrame)
{
    // A joint's three slides as consecutive DOFs are reset together, one slide or two apart (x and z) one by one
    // (RetargetJobTables::translationTriples and translationDofs): moved off rest on input, all are at rest after one
    // frame, and the root's are placed where the source's root goes.
    const ActorDefinitionPtr three = spine("three", 3, 0.2);
    ActorDefinitionBuilder b("sliding");
    b.addJoint("root").offset(0, 0, 1).dofs(kRotationDofs | Dof::TX | Dof::TY | Dof::TZ);
    b.addJoint("s0", "root").dofs(kRotationDofs | Dof::TX | Dof::TY | Dof::TZ);
    b.addJoint("s1", "s0").offset(0, 0, 0.2).dofs(kRotationDofs | Dof::TY);
    b.addJoint("s2", "s1").offset(0, 0, 0.2).dofs(kRotationDofs | Dof::TX | Dof::TZ);
    b.addJoint("head", "s2").offset(0, 0, 0.2).dofs(kRotationDofs);
    b.addJoint("head_end", "head").offset(0, 0, 0.2);
    const ActorDefinitionPtr sliding = b.build().definition;
    ASSERT_TRUE(sliding);
    const std::vector<std::pair<std::string, std::string>> ends = {
        {"root", "HumanoidRoot"}, {"s0", "vl5"}, {"head", "skullbase"}};
    const RetargetRigPtr rig = buildRig(mappedSkeleton(three, ends), mappedSkeleton(sliding, ends));
    ASSERT_TRUE(rig);
    EXPECT_EQ(rig->getJobTables().translationTriples.size(), 2u);
    EXPECT_EQ(rig->getJobTables().translationDofs.size(), 3u);

    const std::vector<double>& rest = rig->getTargetRestDofs();
    std::vector<double> result = rest;
    for (const char* dof : {"root.tx", "s0.tx", "s0.ty", "s0.tz", "s1.ty", "s2.tx", "s2.tz"})
        result[static_cast<unsigned>(sliding->findDof(dof))] += 0.25;
    RetargetWorkspace workspace;
    RetargetJob job = retargetJob(*rig, three->getDefaultDofs(), result, workspace);
    ASSERT_TRUE(job.run());
    for (const char* dof : {"s0.tx", "s0.ty", "s0.tz", "s1.ty", "s2.tx", "s2.tz"})
    {
        const unsigned i = static_cast<unsigned>(sliding->findDof(dof));
        EXPECT_EQ(result[i], rest[i]) << dof;
    }
    // The source stands at rest: the target's root at its own rest place (the hips at their height).
    for (const char* dof : {"root.tx", "root.ty", "root.tz"})
    {
        const unsigned i = static_cast<unsigned>(sliding->findDof(dof));
        EXPECT_NEAR(result[i], rest[i], 1e-12) << dof;
    }
}

TEST(RetargetJob, AHingeStopsAtItsLimitAndTheJointsBelowKeepTheirOrientation)
{
    // The target's knee bends to 90 degrees at most; the source's bends 120. The knee stops at 90 (its DOF within its
    // limits, the joint counted inexact) and the ankle below still turns as the source's does.
    auto leg = [](const std::string& name, double kneeMax) {
        ActorDefinitionBuilder b(name);
        b.addJoint("hip").offset(0, 0, 1).dofs(kRotationDofs);
        b.addJoint("knee", "hip").offset(0, 0, -0.45).dofs(dofBit(Dof::RX)).limits(Dof::RX, 0.0, kneeMax);
        b.addJoint("ankle", "knee").offset(0, 0, -0.45).dofs(kRotationDofs);
        b.addJoint("toe", "ankle").offset(0, -0.15, -0.05);
        return b.build().definition;
    };
    const ActorDefinitionPtr source = leg("source", degrees(150)), target = leg("target", degrees(90));
    const std::vector<std::pair<std::string, std::string>> joints = {
        {"hip", "l_hip"}, {"knee", "l_knee"}, {"ankle", "l_ankle"}};
    const RetargetRigPtr rig = buildRig(mappedSkeleton(source, joints), mappedSkeleton(target, joints));
    ASSERT_TRUE(rig);
    // The same local frames: the joints copy the source's angles, checked against the limits four to a vector, and
    // the knee, beyond its limit there, is clamped one by one.
    unsigned copied = 0;
    for (const RetargetCopyBatch& batch : rig->getJobTables().copyBatches) copied += batch.numJoints;
    EXPECT_EQ(copied, 3u) << "hip, knee and ankle";
    std::vector<double> pose = source->getDefaultDofs();
    pose[static_cast<unsigned>(source->findDof("knee.rx"))] = degrees(120);
    pose[static_cast<unsigned>(source->findDof("ankle.rz"))] = degrees(20);
    RetargetWorkspace workspace;
    std::vector<double> result = target->getDefaultDofs();
    RetargetJob job = retargetJob(*rig, pose, result, workspace);
    ASSERT_TRUE(job.run());
    EXPECT_DOUBLE_EQ(result[static_cast<unsigned>(target->findDof("knee.rx"))], degrees(90));
    EXPECT_EQ(workspace.targetExact[static_cast<unsigned>(target->findJoint("knee"))], 0);
    EXPECT_EQ(job.numInexact, 1u);
    EXPECT_LE(angleBetween(workspace.sourceRotation(static_cast<unsigned>(source->findJoint("ankle"))),
                           workspace.targetRotation(static_cast<unsigned>(target->findJoint("ankle")))),
              1e-12);
}

TEST(RetargetJob, PosesOnlyTheSourceJointsTheRigReadsAndTheyMatchTheFullForwardKinematics)
{
    // 12_03.bvh onto the humanoid, which has no fingers or toes: the job poses the source joints its plans follow, the
    // root, the first joint of every H-Anim joint both have, and their ancestors; those come out as the source's own
    // forward kinematics of the whole skeleton (ActorPose) makes them, and the joints left out change nothing.
    const MocapImport walk = readBvhScaled(repositoryMocap("bvh/12_03.bvh"));
    const ActorDefinitionPtr humanoid = readHumanoid();
    const RetargetRigPtr rig = buildRig(skeleton(walk.definition), skeleton(humanoid));
    ASSERT_TRUE(rig);
    const ActorDefinition& source = *walk.definition;
    const std::vector<std::uint8_t>& read = rig->getJobTables().sourceJointsRead;
    ASSERT_EQ(read.size(), source.getNumJoints());
    for (unsigned j = 0; j < source.getNumJoints(); ++j)
    {
        if (read[j] && source.getParent(j) >= 0)
        {
            EXPECT_TRUE(read[static_cast<unsigned>(source.getParent(j))]) << "the parent of " << source.getJointName(j);
        }
    }
    for (const RetargetJointPlan& plan : rig->getPlans())
    {
        for (int joint : {plan.sourceA, plan.sourceB})
        {
            if (plan.kind != RetargetJointKind::Rest && joint >= 0)
            {
                EXPECT_TRUE(read[static_cast<unsigned>(joint)]);
            }
        }
    }
    for (const char* name : {"Hips", "LeftFoot", "RightHand", "Head"})
        EXPECT_TRUE(read[static_cast<unsigned>(source.findJoint(name))]) << name;
    for (const char* name : {"LThumb", "RightHandIndex1", "LeftToeBase"})
        EXPECT_FALSE(read[static_cast<unsigned>(source.findJoint(name))]) << name;

    RetargetWorkspace workspace, moved;
    std::vector<double> target = rig->getTargetRestDofs(), otherTarget = target;
    for (unsigned f = 0; f < walk.clip->getNumFrames(); f += 50)
    {
        const Span<const double> frame(walk.clip->getFrame(f), walk.clip->getNumChannels());
        RetargetJob job = retargetJob(*rig, frame, target, workspace);
        ASSERT_TRUE(job.run());
        const std::vector<glm::dmat4> full = modelsAt(walk.definition, *walk.clip, f);
        for (unsigned j = 0; j < source.getNumJoints(); ++j)
        {
            if (!read[j]) continue;
            for (int c = 0; c < 4; ++c)
                for (int r = 0; r < 3; ++r)
                    EXPECT_NEAR(workspace.sourceModel(j)[c][r], full[j][c][r], 1e-12) << source.getJointName(j);
        }

        // The same frame with every joint the rig does not read turned: the same target DOFs, to the bit.
        std::vector<double> turned(frame.begin(), frame.end());
        for (unsigned j = 0; j < source.getNumJoints(); ++j)
            if (!read[j])
                for (unsigned d = source.getFirstDof(j); d < source.getFirstDof(j + 1); ++d) turned[d] += 0.5;
        RetargetJob other = retargetJob(*rig, turned, otherTarget, moved);
        ASSERT_TRUE(other.run());
        EXPECT_EQ(otherTarget, target);
    }
}

TEST(RetargetJob, JointsWithOneOrTwoRotationsFittedFourAtATimeTakeTheScalarFitsAngles)
{
    // The humanoid's knees and elbows (one rotation) and ankles and wrists (two) are fitted in vector lanes, depth by
    // depth: on every tenth frame of 12_03.bvh each takes the angles fitJointRotationDofs gives for its desired model
    // rotation (RetargetJointPlan's formula, worked out here with GLM) under its parent's actual one, the previous
    // frame's values as the reference.
    const MocapImport walk = readBvhScaled(repositoryMocap("bvh/12_03.bvh"));
    const ActorDefinitionPtr humanoid = readHumanoid();
    const RetargetRigPtr rig = buildRig(skeleton(walk.definition), skeleton(humanoid));
    ASSERT_TRUE(rig);
    const RetargetJobTables& tables = rig->getJobTables();
    unsigned batchedJoints[3] = {0, 0, 0};
    for (const RetargetAxisBatch& batch : tables.axisBatches) batchedJoints[batch.numRotations] += batch.numJoints;
    EXPECT_EQ(batchedJoints[1], 4u) << "knees and elbows";
    EXPECT_EQ(batchedJoints[2], 4u) << "ankles and wrists";

    const unsigned compared = compareBatchedWithScalarFits(*rig, *walk.clip, tables.inAxisBatch);
    EXPECT_GE(compared, 8u * 50u);
}

TEST(RetargetJob, JointsWithThreeRotationsFittedFourAtATimeTakeTheScalarFitsAngles)
{
    // Boxing_Toes.bvh's joints (three rotations each, orders of its own) are fitted in vector lanes, their Euler
    // inputs read from their frames' and desired rotations' columns: on every tenth frame of 12_03.bvh each takes the
    // angles fitJointRotationDofs gives under its parent's actual rotation. So does every joint of the humanoid with
    // three rotations (limits, so some lanes fall back to the scalar fit).
    const MocapImport walk = readBvhScaled(repositoryMocap("bvh/12_03.bvh"));
    const MocapImport boxing = readBvhScaled(assimpBvh("Boxing_Toes.bvh"), 0.01);
    for (const ActorDefinitionPtr& target : {boxing.definition, readHumanoid()})
    {
        SCOPED_TRACE(target->getName());
        const RetargetRigPtr rig = buildRig(skeleton(walk.definition), skeleton(target));
        ASSERT_TRUE(rig);
        const RetargetJobTables& tables = rig->getJobTables();
        unsigned batchedJoints = 0;
        for (const RetargetEulerBatch& batch : tables.eulerBatches) batchedJoints += batch.numJoints;
        EXPECT_GE(batchedJoints, 4u);
        const unsigned compared = compareBatchedWithScalarFits(*rig, *walk.clip, tables.inEulerBatch);
        EXPECT_GE(compared, batchedJoints * 50u);
    }
}
