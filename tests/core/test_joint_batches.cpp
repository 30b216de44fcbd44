// Forward kinematics builds joints of the same rotation sequence four at a time, one per vector lane (JointBatch):
// the plan that groups them, and that the lanes give each joint the matrix it gets on its own.
#include <osgActor/core/ActorDefinitionBuilder>
#include <osgActor/core/ActorPose>
#include <osgActor/core/LocalMatricesJob>
#include <osgActor/core/LocalToModelJob>

#include "TestMath"

#include <glm/ext/scalar_constants.hpp>

#include <algorithm>
#include <random>
#include <vector>

using namespace osgActor;
using osgActor::test::matricesNear;

namespace {

/** Joints 0..11: a root with translations (built alone), five ZXY joints (a full batch and one more), two XYZ
  * joints, a ZXY joint whose offset is rotated (alone), a joint with no DOF (alone) and two one-axis hinges. */
ActorDefinitionPtr mixedDefinition()
{
    ActorDefinitionBuilder b("mixed");
    b.addJoint("root").dofs(kRotationDofs | dofBit(Dof::TX) | dofBit(Dof::TY) | dofBit(Dof::TZ));
    const char* const zxy[] = {"spine", "neck", "head", "lshoulder", "lelbow"};
    std::string parent = "root";
    for (const char* name : zxy)
    {
        b.addJoint(name, parent).offset(0.1, 0.2, 0.3).dofs(kRotationDofs).eulerOrder(EulerOrder::ZXY);
        parent = name;
    }
    b.addJoint("rshoulder", "spine").offset(-0.2, 0.1, 0).dofs(kRotationDofs).eulerOrder(EulerOrder::XYZ);
    b.addJoint("relbow", "rshoulder").offset(-0.3, 0, 0).dofs(kRotationDofs).eulerOrder(EulerOrder::XYZ);
    b.addJoint("twisted", "root").offset(0, -0.1, 0).rotation(0.4, 0, 1, 0).dofs(kRotationDofs)
        .eulerOrder(EulerOrder::ZXY);
    b.addJoint("fixed", "twisted").offset(0, -0.4, 0);
    b.addJoint("lknee", "root").offset(0.1, -0.5, 0).dofs(dofBit(Dof::RX));
    b.addJoint("rknee", "root").offset(-0.1, -0.5, 0).dofs(dofBit(Dof::RX));
    const BuildResult result = b.build();
    EXPECT_TRUE(result) << result.error;
    return result.definition;
}

/** Every DOF at a random value in [-3, 3]. */
std::vector<double> randomDofs(const ActorDefinition& def, unsigned seed)
{
    std::mt19937 random(seed);
    std::uniform_real_distribution<double> value(-3.0, 3.0);
    std::vector<double> dofs(def.getNumDofs());
    for (double& v : dofs) v = value(random);
    return dofs;
}

} // namespace

TEST(JointBatches, GroupJointsOfOneRotationSequenceInJointOrder)
{
    const ActorDefinitionPtr def = mixedDefinition();
    const JointBatchPlan& plan = def->getJointBatches();
    ASSERT_EQ(plan.batches.size(), 4u);
    const unsigned expectedJoints[4][4] = {{1, 2, 3, 4}, {5, 5, 5, 5}, {6, 7, 7, 7}, {10, 11, 11, 11}};
    const unsigned expectedCounts[4] = {4, 1, 2, 2};
    for (unsigned b = 0; b < 4; ++b)
    {
        const JointBatch& batch = plan.batches[b];
        EXPECT_EQ(batch.numJoints, expectedCounts[b]) << "batch " << b;
        for (unsigned lane = 0; lane < JointBatch::kWidth; ++lane)
        {
            EXPECT_EQ(batch.joints[lane], expectedJoints[b][lane]) << "batch " << b << " lane " << lane;
            const JointKinematics& k = def->getKinematics(batch.joints[lane]);
            EXPECT_EQ(batch.rotationSequence, k.rotationSequence);
            for (unsigned r = 0; r < k.numRotations; ++r)
                EXPECT_EQ(batch.angleDofs[r][lane], k.rotationDof[r]) << "batch " << b << " lane " << lane;
        }
    }
    EXPECT_EQ(plan.singleJoints, (std::vector<std::uint32_t>{0, 8, 9}));
}

TEST(JointBatches, EveryJointIsBuiltExactlyOnce)
{
    const ActorDefinitionPtr def = mixedDefinition();
    const JointBatchPlan& plan = def->getJointBatches();
    std::vector<unsigned> seen(def->getNumJoints(), 0);
    for (const JointBatch& batch : plan.batches)
        for (unsigned lane = 0; lane < batch.numJoints; ++lane) ++seen[batch.joints[lane]];
    for (const std::uint32_t joint : plan.singleJoints) ++seen[joint];
    EXPECT_TRUE(std::all_of(seen.begin(), seen.end(), [](unsigned n) { return n == 1; }));
}

TEST(JointBatches, LanesGiveEachJointItsOwnMatrix)
{
    const ActorDefinitionPtr def = mixedDefinition();
    ActorPose pose(def);
    for (unsigned seed = 1; seed <= 20; ++seed)
    {
        const std::vector<double> dofs = randomDofs(*def, seed);
        ASSERT_EQ(pose.setDofRange(0, dofs.data(), def->getNumDofs()), 0u);
        pose.updateMatrices();
        for (unsigned j = 0; j < def->getNumJoints(); ++j)
            EXPECT_TRUE(matricesNear(pose.getLocalMatrix(j), computeJointMatrix(def->getKinematics(j), dofs.data()),
                                     1e-14))
                << def->getJointName(j) << ", seed " << seed;
    }
}

TEST(JointBatches, ABatchWritesOnlyItsDirtyJoints)
{
    const ActorDefinitionPtr def = mixedDefinition();
    ActorPose pose(def);
    pose.updateMatrices();
    // The nodes' matrices, poisoned: a write to a joint that did not change would show.
    std::vector<glm::dmat4> nodes(def->getNumJoints(), glm::dmat4(7.0));
    std::vector<double*> targets;
    for (glm::dmat4& m : nodes) targets.push_back(&m[0][0]);
    ASSERT_TRUE(pose.redirectLocalMatrices(targets));
    pose.consumeChangedLocals([](unsigned, const double*) {});
    for (glm::dmat4& m : nodes) m = glm::dmat4(7.0);

    // Two joints of the full batch (neck and lshoulder), one of the pair of hinges (rknee).
    std::vector<double> dofs = pose.getDofs();
    const unsigned changed[] = {2, 4, 11};
    for (unsigned joint : changed) dofs[def->getFirstDof(joint)] += 0.5;
    ASSERT_EQ(pose.setDofRange(0, dofs.data(), def->getNumDofs()), 0u);
    EXPECT_EQ(pose.updateMatrices(), 3u);

    std::vector<unsigned> reported;
    pose.consumeChangedLocals([&](unsigned joint, const double*) { reported.push_back(joint); });
    EXPECT_EQ(reported, (std::vector<unsigned>{2, 4, 11}));
    for (unsigned j = 0; j < def->getNumJoints(); ++j)
    {
        const bool isChanged = std::find(std::begin(changed), std::end(changed), j) != std::end(changed);
        if (isChanged)
            EXPECT_TRUE(matricesNear(nodes[j], computeJointMatrix(def->getKinematics(j), dofs.data()), 1e-14))
                << def->getJointName(j);
        else
            EXPECT_TRUE(matricesNear(nodes[j], glm::dmat4(7.0), 0.0)) << def->getJointName(j) << " was written";
    }
    pose.ownLocalMatrices();
}

TEST(JointBatches, AnAngleBeyondTheFastRangeTakesTheLibraryFunctions)
{
    // 1e17 radians is far past the fast range reduction's reach (its quarter-turn count must stay below 2^51):
    // computed there, the matrix would be wrong. Each joint's first angle in turn, batched or not, both when every
    // joint is rebuilt (the range checked as angles are gathered, then all redone) and when that joint alone is (the
    // range checked first).
    const ActorDefinitionPtr def = mixedDefinition();
    for (unsigned joint = 0; joint < def->getNumJoints(); ++joint)
    {
        if (def->getNumJointDofs(joint) == 0) continue;
        const unsigned angle = def->getFirstDof(joint);
        ASSERT_TRUE(isRotation(def->getDofType(angle)));
        std::vector<double> dofs = randomDofs(*def, 3);
        ActorPose pose(def);
        for (const bool everyJoint : {true, false})
        {
            if (!everyJoint)
            {
                pose.updateMatrices();
                dofs[angle] = 0.5;
                ASSERT_EQ(pose.setDofRange(0, dofs.data(), def->getNumDofs()), 0u);
                ASSERT_EQ(pose.updateMatrices(), 1u);
            }
            dofs[angle] = everyJoint ? 1e17 : -3e17;
            ASSERT_EQ(pose.setDofRange(0, dofs.data(), def->getNumDofs()), 0u);
            EXPECT_EQ(pose.updateMatrices(), everyJoint ? def->getNumJoints() : 1u);
            for (unsigned j = 0; j < def->getNumJoints(); ++j)
                EXPECT_TRUE(matricesNear(pose.getLocalMatrix(j), computeJointMatrix(def->getKinematics(j), dofs.data()),
                                         1e-14))
                    << def->getJointName(joint) << " at " << dofs[angle] << ": " << def->getJointName(j);
        }
    }
}

TEST(JointBatches, ModelMatricesComposeAlongChainsAndBranches)
{
    // The model pass keeps a chain's last matrix in registers and reloads a branch's parent from memory: every
    // joint's model matrix is its parent's times its local one, whichever way its parent was reached. Both when
    // every joint moves and when one joint does (its descendants follow).
    const ActorDefinitionPtr def = mixedDefinition();
    ActorPose pose(def);
    const auto expectComposed = [&](const char* when) {
        for (unsigned j = 0; j < def->getNumJoints(); ++j)
        {
            const int parent = def->getParent(j);
            const glm::dmat4 expected = parent < 0 ? pose.getLocalMatrix(j)
                                                   : multiplyAffine(pose.getModelMatrix(static_cast<unsigned>(parent)),
                                                                    pose.getLocalMatrix(j));
            EXPECT_TRUE(matricesNear(pose.getModelMatrix(j), expected, 1e-15)) << when << ": " << def->getJointName(j);
        }
    };
    std::vector<double> dofs = randomDofs(*def, 5);
    ASSERT_EQ(pose.setDofRange(0, dofs.data(), def->getNumDofs()), 0u);
    EXPECT_EQ(pose.updateMatrices(), def->getNumJoints());
    expectComposed("every joint");
    dofs[def->getFirstDof(1)] += 0.5; // spine: its chain and the right arm's branch move
    ASSERT_EQ(pose.setDofRange(0, dofs.data(), def->getNumDofs()), 0u);
    EXPECT_EQ(pose.updateMatrices(), 1u);
    expectComposed("the spine");
}
