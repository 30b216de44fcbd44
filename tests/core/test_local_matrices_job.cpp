// LocalMatricesJob, the first step of forward kinematics: invalid jobs first, then what it rebuilds (only the dirty
// joints, and the flags it leaves), then single joints' skl_m against matrices derived by hand (column-vector
// notation, as in docs/architecture.md).
#include <osgActor/core/ActorDefinitionBuilder>
#include <osgActor/core/LocalMatricesJob>

#include "TestMath"

#include <glm/ext/scalar_constants.hpp>

#include <cmath>
#include <cstdint>
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

/** A chain of three joints, each turning about Z, links 1 long along X: 3 DOFs, one per joint. */
ActorDefinitionPtr threeLinkChain()
{
    ActorDefinitionBuilder b;
    b.addJoint("root").dofs(dofBit(Dof::RZ));
    b.addJoint("elbow", "root").offset(1, 0, 0).dofs(dofBit(Dof::RZ));
    b.addJoint("tip", "elbow").offset(1, 0, 0).dofs(dofBit(Dof::RZ));
    return b.build().definition;
}

/** A job's buffers for a definition: every joint dirty, local matrices all 7 (so what the job writes shows). */
struct Buffers
{
    explicit Buffers(const ActorDefinition& def)
        : dofs(def.getNumDofs(), 0.0), dirty(def.getNumJoints(), 1), localChanged(def.getNumJoints(), 0),
          modelStale(def.getNumJoints(), 0), local(def.getNumJoints(), glm::dmat4(7.0))
    {
        for (glm::dmat4& m : local) targets.push_back(&m[0][0]);
    }
    LocalMatricesJob job(const ActorDefinition& def)
    {
        LocalMatricesJob j;
        j.definition = &def;
        j.dofs = dofs;
        j.jointDirty = dirty;
        j.local = targets;
        j.localChanged = localChanged;
        j.modelStale = modelStale;
        j.numRebuilt = &numRebuilt;
        return j;
    }
    std::vector<double> dofs;
    std::vector<std::uint8_t> dirty, localChanged, modelStale;
    std::vector<glm::dmat4> local;
    std::vector<double*> targets;
    unsigned numRebuilt = 99;
};

} // namespace

// --- invalid jobs are refused and touch nothing ---

TEST(LocalMatricesJob, RefusesAJobWithoutDefinition)
{
    LocalMatricesJob job;
    EXPECT_FALSE(job.validate());
    EXPECT_FALSE(job.run());
}

TEST(LocalMatricesJob, RefusesSpansOfTheWrongSize)
{
    const ActorDefinitionPtr def = threeLinkChain();
    Buffers buffers(*def);
    const std::vector<double> twoDofs(2, 0.0);
    std::vector<std::uint8_t> twoFlags(2, 1);
    const std::vector<double*> twoTargets(buffers.targets.begin(), buffers.targets.begin() + 2);
    for (unsigned wrong = 0; wrong < 5; ++wrong)
    {
        LocalMatricesJob job = buffers.job(*def);
        switch (wrong)
        {
        case 0: job.dofs = twoDofs; break;
        case 1: job.jointDirty = twoFlags; break;
        case 2: job.local = twoTargets; break;
        case 3: job.localChanged = twoFlags; break;
        case 4: job.modelStale = twoFlags; break;
        }
        EXPECT_FALSE(job.validate()) << "span " << wrong;
        EXPECT_FALSE(job.run()) << "span " << wrong;
    }
    EXPECT_EQ(buffers.numRebuilt, 99u) << "a refused run touches nothing";
    EXPECT_EQ(buffers.dirty, std::vector<std::uint8_t>(3, 1));
    EXPECT_EQ(buffers.local[0], glm::dmat4(7.0));
    EXPECT_TRUE(buffers.job(*def).validate());
}

TEST(LocalMatricesJob, AcceptsAnEmptyDofVectorForAnActorWithoutDofs)
{
    ActorDefinitionBuilder b;
    b.addJoint("fixed").offset(1, 2, 3);
    const ActorDefinitionPtr def = b.build().definition;
    Buffers buffers(*def);
    ASSERT_TRUE(buffers.job(*def).run());
    EXPECT_EQ(buffers.numRebuilt, 1u);
    EXPECT_TRUE(matricesNear(buffers.local[0], fromRows(1, 0, 0, 1, 0, 1, 0, 2, 0, 0, 1, 3)));
}

// --- what it rebuilds ---

TEST(LocalMatricesJob, RebuildsOnlyTheDirtyJointsAndMarksThem)
{
    const ActorDefinitionPtr def = threeLinkChain();
    Buffers buffers(*def);
    buffers.dirty = {0, 1, 0};
    buffers.dofs = {0.5, kQuarter, 0.25};
    ASSERT_TRUE(buffers.job(*def).run());
    EXPECT_EQ(buffers.numRebuilt, 1u);
    // The elbow: T(1,0,0) * Rz(90).
    EXPECT_TRUE(matricesNear(buffers.local[1], fromRows(0, -1, 0, 1, 1, 0, 0, 0, 0, 0, 1, 0), 1e-15));
    EXPECT_EQ(buffers.local[0], glm::dmat4(7.0)) << "a clean joint is not written";
    EXPECT_EQ(buffers.local[2], glm::dmat4(7.0));
    EXPECT_EQ(buffers.dirty, (std::vector<std::uint8_t>{0, 0, 0}));
    EXPECT_EQ(buffers.localChanged, (std::vector<std::uint8_t>{0, 1, 0}));
    EXPECT_EQ(buffers.modelStale, (std::vector<std::uint8_t>{0, 1, 0}));
}

TEST(LocalMatricesJob, RebuildsEveryJointWhenAllAreDirty)
{
    const ActorDefinitionPtr def = threeLinkChain();
    Buffers buffers(*def);
    buffers.dofs = {kQuarter, 0.0, -kQuarter};
    ASSERT_TRUE(buffers.job(*def).run());
    EXPECT_EQ(buffers.numRebuilt, 3u);
    EXPECT_TRUE(matricesNear(buffers.local[0], fromRows(0, -1, 0, 0, 1, 0, 0, 0, 0, 0, 1, 0), 1e-15));
    EXPECT_TRUE(matricesNear(buffers.local[1], fromRows(1, 0, 0, 1, 0, 1, 0, 0, 0, 0, 1, 0), 1e-15));
    EXPECT_TRUE(matricesNear(buffers.local[2], fromRows(0, 1, 0, 1, -1, 0, 0, 0, 0, 0, 1, 0), 1e-15));
    EXPECT_EQ(buffers.dirty, std::vector<std::uint8_t>(3, 0));
    EXPECT_EQ(buffers.localChanged, std::vector<std::uint8_t>(3, 1));
    EXPECT_EQ(buffers.modelStale, std::vector<std::uint8_t>(3, 1));
}

TEST(LocalMatricesJob, AnIdleRunRebuildsNothing)
{
    const ActorDefinitionPtr def = threeLinkChain();
    Buffers buffers(*def);
    buffers.dirty.assign(3, 0);
    ASSERT_TRUE(buffers.job(*def).run());
    EXPECT_EQ(buffers.numRebuilt, 0u);
    EXPECT_EQ(buffers.local[1], glm::dmat4(7.0));
    EXPECT_EQ(buffers.localChanged, std::vector<std::uint8_t>(3, 0));
}

// --- one joint's skl_m, as computeJointMatrix (and so the job) builds it ---

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
