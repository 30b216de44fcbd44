#include <osgActor/core/ActorDefinitionBuilder>
#include <osgActor/core/ActorPose>
#include <osgActor/core/LocalMatricesJob>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

using namespace osgActor;

namespace {

const double kNaN = std::numeric_limits<double>::quiet_NaN();
const double kInf = std::numeric_limits<double>::infinity();

/** A five-joint chain with limits on the elbow. */
ActorDefinitionPtr makeArm()
{
    ActorDefinitionBuilder b("arm");
    b.addJoint("shoulder").dofs(kRotationDofs);
    b.addJoint("elbow", "shoulder").offset(0, 0, -0.3).dofs(dofBit(Dof::RX)).limits(Dof::RX, 0.0, 2.5);
    b.addJoint("wrist", "elbow").offset(0, 0, -0.25).dofs(Dof::RX | Dof::RY);
    b.addJoint("hand", "wrist").offset(0, 0, -0.1);
    b.addJoint("slider", "shoulder").dofs(dofBit(Dof::TX)).limits(Dof::TX, -0.1, 0.1);
    return b.build().definition;
}

} // namespace

TEST(ActorPose, RefusesNaNAndInfinityKeepingTheOldValue)
{
    ActorPose pose(makeArm());
    ASSERT_EQ(pose.setDof(3, 1.0), DofWriteStatus::Written);
    pose.updateMatrices();
    EXPECT_EQ(pose.setDof(3, kNaN), DofWriteStatus::NotFinite);
    EXPECT_EQ(pose.setDof(3, kInf), DofWriteStatus::NotFinite);
    EXPECT_EQ(pose.setDof(3, -kInf), DofWriteStatus::NotFinite);
    EXPECT_EQ(pose.getDof(3), 1.0);
    EXPECT_FALSE(pose.hasDirtyJoints()) << "a refused write marks nothing";
}

TEST(ActorPose, RefusesUnknownIndices)
{
    ActorPose pose(makeArm());
    EXPECT_EQ(pose.setDof(pose.getNumDofs(), 0.0), DofWriteStatus::NoSuchDof);
}

TEST(ActorPose, WholePoseWriteIsAllOrNothing)
{
    ActorPose pose(makeArm());
    const std::vector<double> before = pose.getDofs();
    std::vector<double> values(pose.getNumDofs(), 0.5);
    values[4] = kNaN;
    EXPECT_EQ(pose.setDofs(values.data(), values.size()), DofWriteStatus::NotFinite);
    EXPECT_EQ(pose.getDofs(), before);
    EXPECT_EQ(pose.setDofs(values.data(), values.size() - 1), DofWriteStatus::SizeMismatch);
    EXPECT_EQ(pose.getDofs(), before);
    values[4] = 0.5;
    EXPECT_EQ(pose.setDofs(values.data(), values.size()), DofWriteStatus::Clamped) << "slider.tx is clamped";
    EXPECT_EQ(pose.getDof(6), 0.1);
    EXPECT_EQ(pose.getDof(3), 0.5);
}

TEST(ActorPose, LimitsAreEnforcedOnWrite)
{
    ActorPose pose(makeArm());
    EXPECT_EQ(pose.setDof(3, 3.0), DofWriteStatus::Clamped);
    EXPECT_EQ(pose.getDof(3), 2.5);
    EXPECT_EQ(pose.setDof(3, -1.0), DofWriteStatus::Clamped);
    EXPECT_EQ(pose.getDof(3), 0.0);
    EXPECT_EQ(pose.setDof(0, 100.0), DofWriteStatus::Written) << "an unlimited DOF takes any finite value";
}

TEST(ActorPose, NoDofGoesBeyondTheMagnitudeLimitWhateverItsLimits)
{
    // Unlimited DOFs (shoulder.rx, a rotation; a slide without limits) and limits wider than the range alike: a
    // value near the end of the double range would overflow the matrices, so it is clamped to +-kMaxDofMagnitude.
    ActorDefinitionBuilder b("free");
    b.addJoint("root").dofs(dofBit(Dof::RX) | Dof::TX | Dof::TY).limits(Dof::TY, -1e300, 1e200);
    ActorPose pose(b.build().definition);
    const double huge = std::numeric_limits<double>::max();
    for (unsigned d = 0; d < pose.getNumDofs(); ++d)
    {
        EXPECT_EQ(pose.setDof(d, huge), DofWriteStatus::Clamped) << d;
        EXPECT_EQ(pose.getDof(d), kMaxDofMagnitude) << d;
        EXPECT_EQ(pose.setDof(d, -huge), DofWriteStatus::Clamped) << d;
        EXPECT_EQ(pose.getDof(d), -kMaxDofMagnitude) << d;
        EXPECT_EQ(pose.setDof(d, 1e149), DofWriteStatus::Written) << d;
    }
    EXPECT_EQ(pose.getDefinition()->getDofMin(2), -1e300) << "the limits themselves are kept as given";
    EXPECT_EQ(pose.getDefinition()->getDofRangeMin(2), -kMaxDofMagnitude);
    EXPECT_EQ(pose.getDefinition()->getDofRangeMax(2), kMaxDofMagnitude);
}

TEST(ActorPose, OnlyTheChangedJointIsRecomputed)
{
    ActorPose pose(makeArm());
    EXPECT_EQ(pose.updateMatrices(), 5u) << "a new pose computes every joint once";
    EXPECT_EQ(pose.updateMatrices(), 0u) << "an idle pose computes nothing";
    pose.setDof(4, 0.2); // wrist.rx
    EXPECT_TRUE(pose.isJointDirty(2));
    EXPECT_FALSE(pose.isJointDirty(1));
    EXPECT_EQ(pose.updateMatrices(), 1u);
    pose.setDof(4, 0.2);
    EXPECT_FALSE(pose.hasDirtyJoints()) << "writing the value a DOF already has changes nothing";
    pose.setDof(0, 0.1);
    pose.setDof(1, 0.1); // two DOFs of one joint
    pose.setDof(3, 0.4);
    EXPECT_EQ(pose.updateMatrices(), 2u);
    EXPECT_EQ(pose.getTotalRecomputedJoints(), 8u);
}

TEST(ActorPose, ChangedLocalsAreConsumedOnce)
{
    ActorPose pose(makeArm());
    pose.updateMatrices();
    unsigned seen = 0;
    pose.consumeChangedLocals([&](unsigned, const double*) { ++seen; });
    EXPECT_EQ(seen, 5u);
    pose.setDof(3, 1.0);
    pose.updateMatrices();
    pose.setDof(5, 1.0);
    pose.updateMatrices();
    std::vector<unsigned> joints;
    pose.consumeChangedLocals([&](unsigned joint, const double*) { joints.push_back(joint); });
    EXPECT_EQ(joints, (std::vector<unsigned>{1, 2})) << "two runs gathered, each joint once";
    pose.consumeChangedLocals([&](unsigned joint, const double*) { joints.push_back(joint); });
    EXPECT_EQ(joints.size(), 2u);
}

TEST(ActorPose, EveryLocalRebuiltIsReportedInOrderWithItsMatrixThenForgotten)
{
    // Every joint rebuilt (as by a clip playing), then a few more before the changes are consumed: each joint once,
    // in order, with the matrix FK wrote; then nothing until a joint changes again, and then only that joint.
    ActorPose pose(makeArm());
    pose.updateMatrices();
    pose.consumeChangedLocals([](unsigned, const double*) {});
    pose.markAllJointsDirty();
    EXPECT_EQ(pose.updateMatrices(), 5u);
    pose.setDof(3, 0.7);
    EXPECT_EQ(pose.updateMatrices(), 1u);
    std::vector<unsigned> joints;
    std::vector<const double*> matrices;
    pose.consumeChangedLocals([&](unsigned joint, const double* matrix) {
        joints.push_back(joint);
        matrices.push_back(matrix);
    });
    EXPECT_EQ(joints, (std::vector<unsigned>{0, 1, 2, 3, 4}));
    for (unsigned joint = 0; joint < 5 && joint < matrices.size(); ++joint)
        EXPECT_EQ(matrices[joint], pose.getLocalMatrixTargets()[joint]) << "joint " << joint;
    EXPECT_FALSE(pose.hasChangedLocals());
    joints.clear();
    pose.consumeChangedLocals([&](unsigned joint, const double*) { joints.push_back(joint); });
    EXPECT_TRUE(joints.empty());
    pose.setDof(6, 0.05);
    pose.updateMatrices();
    pose.consumeChangedLocals([&](unsigned joint, const double*) { joints.push_back(joint); });
    EXPECT_EQ(joints, (std::vector<unsigned>{4})) << "only the joint that changed since";
}

TEST(ActorPose, CopiesAreIndependent)
{
    ActorPose a(makeArm());
    a.updateMatrices();
    ActorPose b = a;
    b.setDof(3, 1.0);
    b.updateMatrices();
    EXPECT_EQ(a.getDof(3), 0.0);
    EXPECT_NE(a.getModelMatrix(3), b.getModelMatrix(3));
    EXPECT_EQ(a.getDefinition(), b.getDefinition()) << "the definition is shared";
}

TEST(ActorPose, PerJointFlagsStaySeparateInThePoseAndItsCopy)
{
    // Thirteen joints: the flag arrays share one block and are read and written eight bytes at a time, so a count
    // that is no multiple of eight would show a write spilling from one array into the next.
    ActorDefinitionBuilder b("chain");
    b.addJoint("j0").dofs(dofBit(Dof::RX));
    for (int j = 1; j < 13; ++j)
        b.addJoint("j" + std::to_string(j), "j" + std::to_string(j - 1)).offset(0, 0, 0.1).dofs(dofBit(Dof::RX));
    ActorPose pose(b.build().definition);
    ASSERT_EQ(pose.getNumJoints(), 13u);
    pose.updateMatrices();
    pose.consumeChangedLocals([](unsigned, const double*) {});

    const std::vector<double> angles(13, 0.2);
    ASSERT_EQ(pose.setDofRange(0, angles.data(), 13), 0u);
    EXPECT_EQ(pose.updateLocalMatrices(), 13u);
    ASSERT_EQ(pose.setDof(5, 0.4), DofWriteStatus::Written);
    for (unsigned j = 0; j < 13; ++j) EXPECT_EQ(pose.isJointDirty(j), j == 5) << "joint " << j;

    ActorPose copy = pose;
    std::vector<unsigned> changed, changedInCopy;
    copy.consumeChangedLocals([&](unsigned joint, const double*) { changedInCopy.push_back(joint); });
    EXPECT_EQ(changedInCopy.size(), 13u) << "every joint rebuilt, whatever was marked dirty after";
    pose.consumeChangedLocals([&](unsigned joint, const double*) { changed.push_back(joint); });
    EXPECT_EQ(changed, changedInCopy) << "consuming the copy's list leaves the original's";

    EXPECT_EQ(pose.updateMatrices(), 1u) << "only joint 5 was dirty";
    EXPECT_FALSE(pose.isJointDirty(5));
    EXPECT_TRUE(copy.isJointDirty(5)) << "the copy keeps its own dirty flags";
    // The model matrices caught up with every local rebuilt, stale since updateLocalMatrices(): the chain's end
    // turned by 12 x 0.2 + 0.4 about x.
    const glm::dmat4& end = pose.getModelMatrix(12);
    EXPECT_NEAR(end[1][2], std::sin(2.8), 1e-12);
    EXPECT_NEAR(end[1][1], std::cos(2.8), 1e-12);
}

TEST(ActorPose, RedirectedLocalMatricesAreWrittenInPlace)
{
    ActorPose pose(makeArm());
    pose.setDof(3, 0.5); // the elbow
    pose.updateMatrices();
    const glm::dmat4 elbowBefore = pose.getLocalMatrix(1);
    std::vector<glm::dmat4> outside(pose.getNumJoints(), glm::dmat4(0.0));
    std::vector<double*> targets;
    for (glm::dmat4& m : outside) targets.push_back(&m[0][0]);
    ASSERT_TRUE(pose.redirectLocalMatrices(targets));
    EXPECT_EQ(outside[1], elbowBefore) << "the current values are copied to the new place";

    pose.setDof(3, 1.0);
    pose.updateMatrices();
    const double c = std::cos(1.0), s = std::sin(1.0);
    // R_x(1) after the elbow's offset (0, 0, -0.3): column-major, columns x, y, z, translation.
    const glm::dmat4 expected(1, 0, 0, 0, 0, c, s, 0, 0, -s, c, 0, 0, 0, -0.3, 1);
    for (int col = 0; col < 4; ++col)
        for (int row = 0; row < 4; ++row) EXPECT_NEAR(outside[1][col][row], expected[col][row], 1e-15);
    EXPECT_EQ(pose.getLocalMatrix(1), outside[1]) << "the pose reads its matrices where they are";
    EXPECT_EQ(pose.getModelMatrix(2), pose.getModelMatrix(1) * outside[2]) << "model space composes them";

    // A copy owns its matrices: posing it must not write the original's targets.
    ActorPose copy = pose;
    copy.setDof(3, 2.0);
    copy.updateMatrices();
    EXPECT_EQ(outside[1], pose.getLocalMatrix(1));
    EXPECT_NE(copy.getLocalMatrix(1), outside[1]);

    // Taking them back keeps the values and stops writing outside.
    pose.ownLocalMatrices();
    const glm::dmat4 kept = outside[1];
    pose.setDof(3, 1.5);
    pose.updateMatrices();
    EXPECT_EQ(outside[1], kept);
    EXPECT_NE(pose.getLocalMatrix(1), kept);
}

TEST(ActorPose, APosedPoseIsWhatAnUpdateOfANewPoseGives)
{
    ActorPose updated(makeArm());
    EXPECT_EQ(updated.updateMatrices(), updated.getNumJoints());
    ActorPose posed(makeArm(), ActorPose::PosedAtDefaults());
    ASSERT_EQ(posed.getNumJoints(), updated.getNumJoints());
    EXPECT_FALSE(posed.hasDirtyJoints());
    EXPECT_EQ(posed.getTotalRecomputedJoints(), updated.getTotalRecomputedJoints());
    EXPECT_EQ(posed.getDofs(), updated.getDofs());
    for (unsigned j = 0; j < posed.getNumJoints(); ++j)
    {
        EXPECT_EQ(posed.getLocalMatrix(j), updated.getLocalMatrix(j)) << j;
        EXPECT_EQ(posed.getModelMatrix(j), updated.getModelMatrix(j)) << j;
    }
    EXPECT_EQ(posed.getLocalMatrix(1)[3], glm::dvec4(0.0, 0.0, -0.3, 1.0)) << "the elbow's offset";
    unsigned changed = 0;
    posed.consumeChangedLocals([&changed](unsigned, double*) { ++changed; });
    EXPECT_EQ(changed, posed.getNumJoints()) << "every local matrix is new, for the scene graph to take";
    EXPECT_EQ(posed.updateMatrices(), 0u) << "nothing left to do";

    ActorPose empty(nullptr, ActorPose::PosedAtDefaults{});
    EXPECT_EQ(empty.getNumJoints(), 0u);
}

/** The arm with a default pose that is not the identity anywhere, so each joint's matrix tells the joints apart. */
ActorDefinitionPtr makeBentArm()
{
    ActorDefinitionBuilder b("arm");
    b.addJoint("shoulder").dofs(kRotationDofs).defaultValue(Dof::RY, 0.4).defaultValue(Dof::RZ, -0.2);
    b.addJoint("elbow", "shoulder").offset(0, 0, -0.3).dofs(dofBit(Dof::RX)).limits(Dof::RX, 0.0, 2.5)
        .defaultValue(Dof::RX, 1.1);
    b.addJoint("wrist", "elbow").offset(0, 0, -0.25).dofs(Dof::RX | Dof::RY).defaultValue(Dof::RY, -0.7);
    b.addJoint("hand", "wrist").offset(0, 0, -0.1);
    b.addJoint("slider", "shoulder").dofs(dofBit(Dof::TX)).limits(Dof::TX, -0.1, 0.1).defaultValue(Dof::TX, 0.05);
    return b.build().definition;
}

/** Each joint's local matrix at the default DOFs, built where the caller keeps it, as ActorNode does in its nodes. */
std::vector<glm::dmat4> localMatricesBuiltOutside(const ActorDefinition& definition)
{
    std::vector<glm::dmat4> built(definition.getNumJoints(), glm::dmat4(0.0));
    for (unsigned j = 0; j < definition.getNumJoints(); ++j)
        writeJointMatrix(definition.getKinematics(j), definition.getDefaultDofs().data(), &built[j][0][0]);
    return built;
}

TEST(ActorPose, ANullBuiltLocalMatrixOrAWrongCountGivesAPoseWithMatricesOfItsOwn)
{
    const ActorDefinitionPtr arm = makeBentArm();
    ActorPose updated(arm);
    updated.updateMatrices();
    std::vector<glm::dmat4> built = localMatricesBuiltOutside(*arm);
    std::vector<double*> withNull, tooFew;
    for (glm::dmat4& m : built) withNull.push_back(&m[0][0]);
    tooFew = withNull;
    tooFew.pop_back();
    withNull[2] = nullptr;
    for (const std::vector<double*>& targets : {withNull, tooFew})
    {
        ActorPose pose(arm, ActorPose::LocalMatricesBuiltAt{targets});
        ASSERT_EQ(pose.getNumJoints(), arm->getNumJoints());
        EXPECT_NE(pose.getLocalMatrixTargets()[0], &built[0][0][0]) << "matrices of its own";
        for (unsigned j = 0; j < pose.getNumJoints(); ++j)
        {
            EXPECT_EQ(pose.getLocalMatrix(j), updated.getLocalMatrix(j)) << j;
            EXPECT_EQ(pose.getModelMatrix(j), updated.getModelMatrix(j)) << j;
        }
        unsigned changed = 0;
        pose.consumeChangedLocals([&changed](unsigned, double*) { ++changed; });
        EXPECT_EQ(changed, pose.getNumJoints()) << "as PosedAtDefaults: every local matrix new";
    }
}

TEST(ActorPose, APoseTakesLocalMatricesBuiltWhereTheyLiveAndComposesTheModelMatricesOnTheFirstUpdate)
{
    const ActorDefinitionPtr arm = makeBentArm();
    ActorPose updated(arm);
    updated.updateMatrices();
    std::vector<glm::dmat4> built = localMatricesBuiltOutside(*arm);
    std::vector<double*> targets;
    for (glm::dmat4& m : built) targets.push_back(&m[0][0]);

    ActorPose pose(arm, ActorPose::LocalMatricesBuiltAt{targets});
    ASSERT_EQ(pose.getNumJoints(), arm->getNumJoints());
    EXPECT_FALSE(pose.hasDirtyJoints());
    EXPECT_FALSE(pose.hasChangedLocals()) << "the caller has them where they are shown";
    EXPECT_EQ(pose.getTotalRecomputedJoints(), updated.getTotalRecomputedJoints());
    for (unsigned j = 0; j < pose.getNumJoints(); ++j)
    {
        EXPECT_EQ(pose.getLocalMatrixTargets()[j], targets[j]) << j;
        EXPECT_EQ(pose.getLocalMatrix(j), updated.getLocalMatrix(j)) << j;
    }
    // The elbow: offset (0, 0, -0.3), turned 1.1 radians about x (local space).
    EXPECT_EQ(pose.getLocalMatrix(1)[3], glm::dvec4(0.0, 0.0, -0.3, 1.0));
    EXPECT_NEAR(pose.getLocalMatrix(1)[1][1], std::cos(1.1), 1e-15);
    EXPECT_NEAR(pose.getLocalMatrix(1)[1][2], std::sin(1.1), 1e-15);

    EXPECT_EQ(pose.updateMatrices(), 0u) << "no local matrix to rebuild";
    for (unsigned j = 0; j < pose.getNumJoints(); ++j)
        EXPECT_EQ(pose.getModelMatrix(j), updated.getModelMatrix(j)) << j;
    pose.setDof(3, 0.5); // the elbow
    pose.updateMatrices();
    EXPECT_NEAR(built[1][1][1], std::cos(0.5), 1e-15) << "forward kinematics writes where the matrices live";

    ActorPose empty(nullptr, ActorPose::LocalMatricesBuiltAt{});
    EXPECT_EQ(empty.getNumJoints(), 0u);
}

TEST(ActorPose, ARedirectToMatricesThatHoldTheValuesCopiesNothing)
{
    ActorPose pose(makeArm());
    pose.setDof(3, 0.5); // the elbow
    pose.updateMatrices();
    // The caller put the current values in place itself, except for one it left as a marker.
    std::vector<glm::dmat4> outside(pose.getNumJoints());
    std::vector<double*> targets;
    for (unsigned j = 0; j < pose.getNumJoints(); ++j)
    {
        outside[j] = pose.getLocalMatrix(j);
        targets.push_back(&outside[j][0][0]);
    }
    outside[4] = glm::dmat4(2.0);
    ASSERT_TRUE(pose.redirectLocalMatrices(targets, LocalMatrices::Values::AlreadyThere));
    EXPECT_EQ(pose.getLocalMatrix(4), glm::dmat4(2.0)) << "the pose now reads them where they are, as they are";
    EXPECT_EQ(pose.getLocalMatrixTargets()[1], &outside[1][0][0]);
    pose.setDof(3, 1.0);
    pose.updateMatrices();
    EXPECT_NEAR(outside[1][1][1], std::cos(1.0), 1e-15) << "and writes them there";
}

TEST(ActorPose, RefusesBadLocalMatrixTargets)
{
    ActorPose pose(makeArm());
    pose.updateMatrices();
    std::vector<glm::dmat4> outside(pose.getNumJoints());
    std::vector<double*> targets;
    for (glm::dmat4& m : outside) targets.push_back(&m[0][0]);
    targets.pop_back();
    EXPECT_FALSE(pose.redirectLocalMatrices(targets)) << "one short";
    targets.push_back(nullptr);
    EXPECT_FALSE(pose.redirectLocalMatrices(targets)) << "a null target";
    pose.setDof(3, 1.0);
    pose.updateMatrices();
    EXPECT_NE(pose.getLocalMatrix(1), glm::dmat4(1.0)) << "still its own matrices";
}

TEST(ActorPose, ARangeWriteFollowsTheRulesOfSetDof)
{
    ActorPose pose(makeArm());
    pose.updateMatrices();
    // DOFs 3..6: elbow.rx in [0, 2.5], wrist.rx, wrist.ry, slider.tx in [-0.1, 0.1].
    const double values[] = {3.0, kNaN, 0.2, 0.5};
    EXPECT_EQ(pose.setDofRange(3, values, 4), 1u) << "the NaN is refused";
    EXPECT_EQ(pose.getDof(3), 2.5) << "clamped";
    EXPECT_EQ(pose.getDof(4), 0.0) << "the refused value keeps the old one";
    EXPECT_EQ(pose.getDof(5), 0.2);
    EXPECT_EQ(pose.getDof(6), 0.1) << "clamped";
    EXPECT_FALSE(pose.isJointDirty(0)) << "the shoulder was not written";
    EXPECT_TRUE(pose.isJointDirty(1));
    EXPECT_TRUE(pose.isJointDirty(2));
    EXPECT_FALSE(pose.isJointDirty(3)) << "the hand has no DOF";
    EXPECT_TRUE(pose.isJointDirty(4));
    pose.updateMatrices();
    const double same[] = {2.5, 0.0, 0.2, 0.1};
    EXPECT_EQ(pose.setDofRange(3, same, 4), 0u);
    EXPECT_FALSE(pose.hasDirtyJoints()) << "values already held mark nothing";
    const double inf[] = {kInf};
    EXPECT_EQ(pose.setDofRange(0, inf, 1), 1u);
    EXPECT_EQ(pose.setDofRange(5, values, 3), 3u) << "past the end: all refused";
    EXPECT_EQ(pose.getDof(5), 0.2);
    EXPECT_FALSE(pose.hasDirtyJoints());
}

TEST(ActorPose, ALongRangeWriteMarksOnlyTheJointsThatChanged)
{
    // 60 joints of 3 DOFs: 180 DOFs, more than one block of the range write; joint 42 straddles DOF 128.
    ActorDefinitionBuilder b("snake");
    b.addJoint("j0").dofs(kRotationDofs);
    for (unsigned j = 1; j < 60; ++j)
        b.addJoint("j" + std::to_string(j), "j" + std::to_string(j - 1)).offset(0, 0, 0.1).dofs(kRotationDofs);
    ActorPose pose(b.build().definition);
    pose.updateMatrices();
    std::vector<double> values(pose.getDofs());
    values[128] = 0.5; // joint 42's third DOF
    values[10] = 0.25; // joint 3
    EXPECT_EQ(pose.setDofRange(0, values.data(), 180), 0u);
    for (unsigned j = 0; j < 60; ++j) EXPECT_EQ(pose.isJointDirty(j), j == 42 || j == 3) << "joint " << j;
    EXPECT_EQ(pose.getDofs(), values);
}

TEST(ActorPose, ARangeWriteThatChangesEveryDofMarksExactlyTheJointsOwningThem)
{
    // 100 joints, every third one without a DOF (an end site), the others with 2 or 3: 168 DOFs. A write of which
    // every value is new takes the all-changed path, eight joints a step; joints without a DOF between those
    // written, and joints outside the range, stay clean. Two ranges: 165 DOFs (two 128-DOF blocks), and a short one.
    ActorDefinitionBuilder b("comb");
    b.addJoint("j0").dofs(kRotationDofs);
    for (unsigned j = 1; j < 100; ++j)
    {
        auto joint = b.addJoint("j" + std::to_string(j), "j0");
        if (j % 3 == 1) joint.dofs(Dof::RX | Dof::RZ);
        else if (j % 3 == 2) joint.dofs(kRotationDofs);
    }
    ActorPose pose(b.build().definition);
    const ActorDefinition& def = *pose.getDefinition();
    for (const unsigned firstJoint : {1u, 40u})
    {
        pose.updateMatrices();
        const unsigned lastJoint = firstJoint == 1 ? 98 : 44; // both have DOFs
        const unsigned firstDof = def.getFirstDof(firstJoint), endDof = def.getFirstDof(lastJoint + 1);
        std::vector<double> values(pose.getDofs().begin() + firstDof, pose.getDofs().begin() + endDof);
        for (double& v : values) v += 0.125;
        EXPECT_EQ(pose.setDofRange(firstDof, values.data(), endDof - firstDof), 0u);
        for (unsigned j = 0; j < def.getNumJoints(); ++j)
        {
            const bool written = j >= firstJoint && j <= lastJoint && def.getNumJointDofs(j) > 0;
            EXPECT_EQ(pose.isJointDirty(j), written) << "range from joint " << firstJoint << ", joint " << j;
        }
        EXPECT_EQ(pose.updateMatrices(), firstJoint == 1 ? 66u : 4u) << "joints rebuilt";
    }
}

TEST(ActorPose, MatrixArraysStartOnACacheLine)
{
    // So that no 32-byte column the FK loops load or store straddles two cache lines; copies too.
    ActorPose pose(makeArm());
    const ActorPose copy = pose;
    for (const ActorPose* p : {static_cast<const ActorPose*>(&pose), &copy})
        EXPECT_EQ(reinterpret_cast<std::uintptr_t>(&p->getModelMatrix(0)) % 64, 0u);
}

TEST(ActorPose, ResetRestoresDefaults)
{
    ActorPose pose(makeArm());
    pose.setDof(0, 1.0);
    pose.resetDofs();
    EXPECT_EQ(pose.getDofs(), pose.getDefinition()->getDefaultDofs());
}

TEST(ActorPose, AnEmptyPoseIsHarmless)
{
    ActorPose pose;
    EXPECT_EQ(pose.getNumDofs(), 0u);
    EXPECT_EQ(pose.updateMatrices(), 0u);
    EXPECT_EQ(pose.setDof(0, 1.0), DofWriteStatus::NoSuchDof);
    pose.resetDofs();
}
