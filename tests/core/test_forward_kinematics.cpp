// Forward kinematics through the pose (LocalMatricesJob, then LocalToModelJob) against positions derived by hand
// (column-vector notation, as in docs/architecture.md), and the batched sine and cosine it is built on.
#include <osgActor/core/ActorDefinitionBuilder>
#include <osgActor/core/ActorPose>
#include <osgActor/core/detail/SinCos>

#include "TestMath"

#include <glm/ext/scalar_constants.hpp>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <random>
#include <string>
#include <vector>

using namespace osgActor;
using osgActor::test::vectorsNear;

namespace {

const double kQuarter = glm::pi<double>() / 2.0;

} // namespace

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

// --- the batched trigonometry the local-matrices job is built on ---

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
