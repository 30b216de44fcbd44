// Forward kinematics against matrices derived by hand (column-vector notation, as in docs/architecture.md).
#include <osgActor/core/ActorDefinitionBuilder>
#include <osgActor/core/ActorPose>
#include <osgActor/core/ForwardKinematicsJob>
#include <osgActor/core/SinCos>

#include "TestMath"

#include <glm/ext/scalar_constants.hpp>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <random>
#include <string>
#include <vector>

using namespace osgActor;
using osgActor::test::fromRows;
using osgActor::test::matricesNear;
using osgActor::test::vectorsNear;

namespace {

const double kQuarter = glm::pi<double>() / 2.0;

/** One joint's local matrix for the given DOF values (in DOF-vector order). */
glm::dmat4 jointMatrix(ActorDefinitionBuilder& builder, const std::vector<double>& dofs, unsigned joint = 0)
{
    const BuildResult result = builder.build();
    EXPECT_TRUE(result) << result.error;
    if (!result) return glm::dmat4(0.0);
    return computeJointMatrix(result.definition->getKinematics(joint), dofs.data());
}

} // namespace

// --- the job refuses missing buffers first ---

TEST(ForwardKinematicsJob, RefusesMissingBuffers)
{
    ActorDefinitionBuilder b;
    b.addJoint("root").dofs(dofBit(Dof::RX));
    const ActorDefinitionPtr def = b.build().definition;
    std::vector<double> dofs(1, 0.0);
    std::vector<std::uint8_t> dirty(1, 1), localChanged(1, 0), modelStale(1, 0), modelChanged(1, 0);
    std::vector<glm::dmat4> local(1), model(1);
    double* const localTargets[1] = {&local[0][0][0]};

    ForwardKinematicsJob job;
    EXPECT_FALSE(job.validate());
    job.definition = def.get();
    job.jointDirty = dirty.data();
    job.local = localTargets;
    job.model = model.data();
    job.localChanged = localChanged.data();
    job.modelChanged = modelChanged.data();
    EXPECT_FALSE(job.validate()) << "no model-stale flags";
    job.modelStale = modelStale.data();
    EXPECT_FALSE(job.validate()) << "no DOF vector for an actor that has DOFs";
    EXPECT_FALSE(job.run());
    EXPECT_EQ(dirty[0], 1) << "a refused run touches nothing";
    job.dofs = dofs.data();
    job.model = nullptr;
    EXPECT_FALSE(job.validate());
    job.model = model.data();
    EXPECT_TRUE(job.run());
    EXPECT_EQ(job.numRecomputed, 1u);
    EXPECT_EQ(dirty[0], 0);
}

// --- single joints ---

TEST(JointMatrix, NoActiveDofIsTheOffset)
{
    ActorDefinitionBuilder b;
    b.addJoint("fixed").offset(1, 2, 3);
    EXPECT_TRUE(matricesNear(jointMatrix(b, {}), fromRows(1, 0, 0, 1, 0, 1, 0, 2, 0, 0, 1, 3)));
}

TEST(JointMatrix, RotationAboutXAfterTheOffset)
{
    // Rx(90): y -> z, z -> -y; the offset translation stays in column 3.
    ActorDefinitionBuilder b;
    b.addJoint("j").offset(1, 2, 3).dofs(dofBit(Dof::RX));
    EXPECT_TRUE(matricesNear(jointMatrix(b, {kQuarter}), fromRows(1, 0, 0, 1, 0, 0, -1, 2, 0, 1, 0, 3), 1e-15));
}

TEST(JointMatrix, PaperOrderSlidesAlongTheRotatedX)
{
    // offset T(0,0,1) * Rz(90) * Tx(2): the joint origin goes (2,0,0) -> (0,2,0) -> (0,2,1).
    ActorDefinitionBuilder b;
    b.addJoint("j").offset(0, 0, 1).dofs(kPaperDofs);
    const glm::dmat4 m = jointMatrix(b, {0.0, 0.0, kQuarter, 2.0});
    EXPECT_TRUE(matricesNear(m, fromRows(0, -1, 0, 0, 1, 0, 0, 2, 0, 0, 1, 1), 1e-15));
}

TEST(JointMatrix, TranslationBeforeRotationStaysInTheOffsetFrame)
{
    // offset T(1,0,0) * T(2,0,0) * Rz(90): translation (3,0,0), rotation Rz(90).
    ActorDefinitionBuilder b;
    b.addJoint("j").offset(1, 0, 0).dofs(Dof::RZ | Dof::TX).translationMode(TranslationMode::BeforeRotation);
    EXPECT_TRUE(matricesNear(jointMatrix(b, {kQuarter, 2.0}), fromRows(0, -1, 0, 3, 1, 0, 0, 0, 0, 0, 1, 0), 1e-15));
}

TEST(JointMatrix, EulerOrderXYZIsRxTimesRy)
{
    // Rx(90) * Ry(90) = [[0,0,1],[1,0,0],[0,1,0]] worked by hand row by row.
    ActorDefinitionBuilder b;
    b.addJoint("j").dofs(Dof::RX | Dof::RY);
    EXPECT_TRUE(
        matricesNear(jointMatrix(b, {kQuarter, kQuarter}), fromRows(0, 0, 1, 0, 1, 0, 0, 0, 0, 1, 0, 0), 1e-15));
}

TEST(JointMatrix, EulerOrderYXZIsRyTimesRx)
{
    // Ry(90) * Rx(90) = [[0,1,0],[0,0,-1],[-1,0,0]].
    ActorDefinitionBuilder b;
    b.addJoint("j").dofs(Dof::RX | Dof::RY).eulerOrder(EulerOrder::YXZ);
    EXPECT_TRUE(
        matricesNear(jointMatrix(b, {kQuarter, kQuarter}), fromRows(0, 1, 0, 0, 0, 0, -1, 0, -1, 0, 0, 0), 1e-15));
}

TEST(JointMatrix, ThreeRotationsInEveryOrderMatchTheProductOfAxisMatrices)
{
    // Against an independent product of elementary matrices written out in rows.
    const double ax = 0.3, ay = -1.1, az = 2.0;
    const glm::dmat4 rx = fromRows(1, 0, 0, 0, 0, std::cos(ax), -std::sin(ax), 0, 0, std::sin(ax), std::cos(ax), 0);
    const glm::dmat4 ry = fromRows(std::cos(ay), 0, std::sin(ay), 0, 0, 1, 0, 0, -std::sin(ay), 0, std::cos(ay), 0);
    const glm::dmat4 rz = fromRows(std::cos(az), -std::sin(az), 0, 0, std::sin(az), std::cos(az), 0, 0, 0, 0, 1, 0);
    const glm::dmat4* byAxis[3] = {&rx, &ry, &rz};
    for (unsigned o = 0; o < 6; ++o)
    {
        const EulerOrder order = static_cast<EulerOrder>(o);
        unsigned axes[3];
        eulerOrderAxes(order, axes);
        ActorDefinitionBuilder b;
        b.addJoint("j").dofs(kRotationDofs).eulerOrder(order);
        const glm::dmat4 expected = *byAxis[axes[0]] * *byAxis[axes[1]] * *byAxis[axes[2]];
        EXPECT_TRUE(matricesNear(jointMatrix(b, {ax, ay, az}), expected, 1e-14)) << eulerOrderName(order);
    }
}

TEST(JointMatrix, OffsetRotationComesBeforeTheArticulation)
{
    // T(0,1,0) * Rz(90) * Rx(90) = rotation [[0,0,1],[1,0,0],[0,1,0]], translation (0,1,0).
    ActorDefinitionBuilder b;
    b.addJoint("j").offset(0, 1, 0).rotation(kQuarter, 0, 0, 1).dofs(dofBit(Dof::RX));
    EXPECT_TRUE(matricesNear(jointMatrix(b, {kQuarter}), fromRows(0, 0, 1, 0, 1, 0, 0, 1, 0, 1, 0, 0), 1e-15));
}

TEST(JointMatrix, TranslationExtensionsTyTz)
{
    // offset T(1,1,1) * Rx(90) * T(0, 2, 3): (0,2,3) rotated by Rx(90) is (0,-3,2).
    ActorDefinitionBuilder b;
    b.addJoint("j").offset(1, 1, 1).dofs(Dof::RX | Dof::TY | Dof::TZ);
    const glm::dmat4 m = jointMatrix(b, {kQuarter, 2.0, 3.0});
    EXPECT_TRUE(vectorsNear(glm::dvec3(m[3]), glm::dvec3(1.0, -2.0, 3.0), 1e-15));
}

// --- chains through the pose ---

TEST(ForwardKinematics, ChainModelMatricesCompose)
{
    // Root turned 90 about Z; each link 1 long along X and turned 90 more: joints at (0,0,0), (0,1,0), (-1,1,0).
    ActorDefinitionBuilder b;
    b.addJoint("root").dofs(dofBit(Dof::RZ));
    b.addJoint("elbow", "root").offset(1, 0, 0).dofs(dofBit(Dof::RZ));
    b.addJoint("tip", "elbow").offset(1, 0, 0);
    ActorPose pose(b.build().definition);
    ASSERT_EQ(pose.setDof(0, kQuarter), DofWriteStatus::Written);
    ASSERT_EQ(pose.setDof(1, kQuarter), DofWriteStatus::Written);
    pose.updateMatrices();
    EXPECT_TRUE(vectorsNear(glm::dvec3(pose.getModelMatrix(0)[3]), glm::dvec3(0, 0, 0), 1e-15));
    EXPECT_TRUE(vectorsNear(glm::dvec3(pose.getModelMatrix(1)[3]), glm::dvec3(0, 1, 0), 1e-15));
    EXPECT_TRUE(vectorsNear(glm::dvec3(pose.getModelMatrix(2)[3]), glm::dvec3(-1, 1, 0), 1e-15));
    // The tip's X axis points along -X after two quarter turns.
    EXPECT_TRUE(vectorsNear(glm::dvec3(pose.getModelMatrix(2)[0]), glm::dvec3(-1, 0, 0), 1e-15));
}

TEST(ForwardKinematics, ModelMatricesCanWaitUntilAsked)
{
    ActorDefinitionBuilder b;
    b.addJoint("root").dofs(dofBit(Dof::RZ));
    b.addJoint("elbow", "root").offset(1, 0, 0).dofs(dofBit(Dof::RZ));
    b.addJoint("tip", "elbow").offset(1, 0, 0);
    ActorPose pose(b.build().definition);
    pose.updateMatrices();
    pose.setDof(0, kQuarter);
    EXPECT_EQ(pose.updateLocalMatrices(), 1u);
    EXPECT_TRUE(vectorsNear(glm::dvec3(pose.getModelMatrix(2)[3]), glm::dvec3(2, 0, 0), 1e-15)) << "still stale";
    EXPECT_EQ(pose.updateMatrices(), 0u) << "no local matrix left to rebuild";
    EXPECT_TRUE(vectorsNear(glm::dvec3(pose.getModelMatrix(2)[3]), glm::dvec3(0, 2, 0), 1e-15)) << "now current";
}

TEST(ForwardKinematics, MovingAParentMovesItsChildrenButRecomputesOneJoint)
{
    ActorDefinitionBuilder b;
    b.addJoint("root").dofs(dofBit(Dof::RZ));
    b.addJoint("elbow", "root").offset(1, 0, 0).dofs(dofBit(Dof::RZ));
    b.addJoint("tip", "elbow").offset(1, 0, 0);
    ActorPose pose(b.build().definition);
    EXPECT_EQ(pose.updateMatrices(), 3u);
    pose.setDof(0, kQuarter);
    EXPECT_EQ(pose.updateMatrices(), 1u);
    EXPECT_TRUE(vectorsNear(glm::dvec3(pose.getModelMatrix(2)[3]), glm::dvec3(0, 2, 0), 1e-15));
}

TEST(ForwardKinematics, OneCleanJointAnywhereKeepsTheRebuildToTheDirtyOnes)
{
    // Every joint dirty takes a path without per-joint flag tests; a single clean joint, wherever it stands among
    // the flags (the test reads them eight at a time, the last eight overlapping), must keep FK on the path that
    // rebuilds only the dirty ones.
    for (unsigned numJoints : {3u, 8u, 9u, 16u, 31u})
    {
        ActorDefinitionBuilder b;
        b.addJoint("j0").dofs(dofBit(Dof::RZ));
        for (unsigned j = 1; j < numJoints; ++j)
            b.addJoint("j" + std::to_string(j), "j" + std::to_string(j - 1)).offset(1, 0, 0).dofs(dofBit(Dof::RZ));
        const ActorDefinitionPtr definition = b.build().definition;
        for (unsigned clean = 0; clean < numJoints; ++clean)
        {
            ActorPose pose(definition);
            pose.updateMatrices();
            for (unsigned j = 0; j < numJoints; ++j)
                if (j != clean) pose.setDof(j, 0.1);
            EXPECT_EQ(pose.updateMatrices(), numJoints - 1) << numJoints << " joints, joint " << clean << " clean";
            // A chain of links 1 long, each turned 0.1 more but the clean one: the tip's model matrix says so.
            double angle = 0.0;
            glm::dvec3 tip(0.0);
            for (unsigned j = 0; j < numJoints; ++j)
            {
                if (j > 0) tip += glm::dvec3(std::cos(angle), std::sin(angle), 0.0);
                angle += j == clean ? 0.0 : 0.1;
            }
            EXPECT_TRUE(vectorsNear(glm::dvec3(pose.getModelMatrix(numJoints - 1)[3]), tip, 1e-12)) << clean;
        }
    }
}

// --- the batched trigonometry and the affine product the job is built on ---

TEST(SinCos, MatchesTheScalarFunctionsToAFewUlp)
{
    std::mt19937 random(7);
    std::uniform_real_distribution<double> small(-7.0, 7.0), large(-1000.0, 1000.0);
    std::vector<double> angles;
    for (int i = 0; i < 1000; ++i) angles.push_back(i % 2 ? small(random) : large(random));
    angles.push_back(0.0);
    angles.push_back(-0.0);
    angles.push_back(1e-300);
    // Either side of the quadrant boundaries, where the range reduction switches between sine and cosine.
    for (int k = -8; k <= 8; ++k)
        for (double nudge : {-1e-9, 0.0, 1e-9}) angles.push_back(k * 1.5707963267948966 + nudge);
    // Beyond the fast path's range (1e6): the library's functions.
    angles.push_back(2.5e6);
    angles.push_back(-1e9);
    std::vector<double> sines(angles.size()), cosines(angles.size());
    sinCos(angles.data(), sines.data(), cosines.data(), static_cast<unsigned>(angles.size()));
    for (unsigned i = 0; i < angles.size(); ++i)
    {
        EXPECT_NEAR(sines[i], std::sin(angles[i]), 1e-15) << angles[i];
        EXPECT_NEAR(cosines[i], std::cos(angles[i]), 1e-15) << angles[i];
    }
}

TEST(SinCos, ATailOfOneToThreeAnglesMatchesTheFullColumns)
{
    // Four at a time, then the last one to three padded: every count must give the values a longer run gives.
    const double angles[8] = {0.1, -2.0, 3.5, 7.0, -0.7, 1.2e3, 2.5e6, 4.0};
    double fullSines[8], fullCosines[8];
    sinCos(angles, fullSines, fullCosines, 8);
    for (unsigned count = 1; count < 8; ++count)
    {
        double sines[8], cosines[8];
        std::fill(std::begin(sines), std::end(sines), -9.0);
        std::fill(std::begin(cosines), std::end(cosines), -9.0);
        sinCos(angles, sines, cosines, count);
        for (unsigned i = 0; i < 8; ++i)
        {
            EXPECT_EQ(sines[i], i < count ? fullSines[i] : -9.0) << "count " << count << ", angle " << i;
            EXPECT_EQ(cosines[i], i < count ? fullCosines[i] : -9.0) << "count " << count << ", angle " << i;
        }
    }
}

TEST(MultiplyAffine, EqualsTheFullProduct)
{
    const glm::dmat4 a = fromRows(0.2, -0.9, 0.1, 4, 0.7, 0.3, -0.5, -2, 0.1, 0.4, 0.8, 1);
    const glm::dmat4 b = fromRows(1, 2, 3, 4, -1, 0.5, 2, 5, 0, 0.25, -3, 6);
    EXPECT_TRUE(matricesNear(multiplyAffine(a, b), a * b, 1e-14));
}

TEST(ForwardKinematics, ModelMatricesCanCatchUpWithoutApplyingNewDofs)
{
    ActorDefinitionBuilder b;
    b.addJoint("root").dofs(dofBit(Dof::RZ));
    b.addJoint("tip", "root").offset(1, 0, 0);
    ActorPose pose(b.build().definition);
    pose.setDof(0, kQuarter);
    pose.updateLocalMatrices(); // what the nodes show: turned a quarter
    pose.setDof(0, 0.0);        // a later write, not applied
    pose.updateModelMatrices();
    EXPECT_TRUE(vectorsNear(glm::dvec3(pose.getModelMatrix(1)[3]), glm::dvec3(0, 1, 0), 1e-15));
    EXPECT_TRUE(pose.isJointDirty(0)) << "the new value is still waiting";
    pose.updateMatrices();
    EXPECT_TRUE(vectorsNear(glm::dvec3(pose.getModelMatrix(1)[3]), glm::dvec3(1, 0, 0), 1e-15));
}
