// IK chain descriptions: what buildIkChain refuses (and why), and what a built chain holds.
#include "IkTestUtil"

#include <glm/geometric.hpp>

#include <limits>

using namespace osgActor;
using namespace osgActor::test;

namespace {

/** The refusal message for a spec, failing the test if the spec was accepted. */
std::string refusal(const ActorDefinition& definition, const IkChainSpec& spec)
{
    const IkChainBuildResult result = buildIkChain(definition, spec);
    EXPECT_FALSE(result) << "accepted chain '" << spec.name << "'";
    EXPECT_EQ(result.chain, nullptr);
    return result.error;
}

::testing::AssertionResult mentions(const std::string& text, const std::string& part)
{
    if (text.find(part) != std::string::npos) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << "'" << text << "' does not mention '" << part << "'";
}

} // namespace

TEST(IkChainBuild, RefusesUnknownJoints)
{
    const ActorDefinitionPtr leg = makeLegActor();
    EXPECT_TRUE(
        mentions(refusal(*leg, chainSpec("c", "thigh", "ankle", IkSolverType::Dls)), "no root joint named 'thigh'"));
    EXPECT_TRUE(
        mentions(refusal(*leg, chainSpec("c", "hip", "foot", IkSolverType::Dls)), "no effector joint named 'foot'"));
}

TEST(IkChainBuild, RefusesAnEffectorNotBelowTheRoot)
{
    const ActorDefinitionPtr leg = makeLegActor();
    EXPECT_TRUE(mentions(refusal(*leg, chainSpec("c", "ankle", "hip", IkSolverType::Dls)),
                         "effector 'hip' is not below root 'ankle'"));
    // A sibling branch is not below either.
    ActorDefinitionBuilder b("two legs");
    b.addJoint("pelvis").dofs(kRotationDofs);
    b.addJoint("l_hip", "pelvis").offset(0.1, 0, 0).dofs(kRotationDofs);
    b.addJoint("l_knee", "l_hip").offset(0, -0.4, 0).dofs(dofBit(Dof::RX));
    b.addJoint("r_hip", "pelvis").offset(-0.1, 0, 0).dofs(kRotationDofs);
    const ActorDefinitionPtr legs = b.build().definition;
    EXPECT_TRUE(mentions(refusal(*legs, chainSpec("c", "r_hip", "l_knee", IkSolverType::Dls)), "is not below root"));
}

TEST(IkChainBuild, RefusesZeroLengthChains)
{
    const ActorDefinitionPtr leg = makeLegActor();
    EXPECT_TRUE(mentions(refusal(*leg, chainSpec("c", "knee", "knee", IkSolverType::Dls)), "at least one bone"));
    ActorDefinitionBuilder b("stacked");
    b.addJoint("a").dofs(kRotationDofs);
    b.addJoint("b", "a").dofs(kRotationDofs); // no offset: the bone has no length
    const ActorDefinitionPtr stacked = b.build().definition;
    EXPECT_TRUE(mentions(refusal(*stacked, chainSpec("c", "a", "b", IkSolverType::Dls)), "bones have no length"));
    // An effector offset gives it a length.
    EXPECT_TRUE(buildIkChain(*stacked, chainSpec("c", "a", "b", IkSolverType::Dls, glm::dvec3(0, 0.1, 0))));
}

TEST(IkChainBuild, RefusesBadNumbers)
{
    const ActorDefinitionPtr leg = makeLegActor();
    const double nan = std::numeric_limits<double>::quiet_NaN();
    IkChainSpec spec = chainSpec("leg", "hip", "ankle", IkSolverType::Dls, glm::dvec3(0, nan, 0));
    EXPECT_TRUE(mentions(refusal(*leg, spec), "effector offset is not finite"));
    spec = chainSpec("leg", "hip", "ankle", IkSolverType::Dls);
    spec.maxIterations = 0;
    EXPECT_TRUE(mentions(refusal(*leg, spec), "at least one iteration"));
    for (double tolerance : {0.0, -1e-3, 1.0, nan})
    {
        spec = chainSpec("leg", "hip", "ankle", IkSolverType::Dls);
        spec.tolerance = tolerance;
        EXPECT_TRUE(mentions(refusal(*leg, spec), "is not in (0, 1)")) << tolerance;
    }
    spec = chainSpec("", "hip", "ankle", IkSolverType::Dls);
    EXPECT_TRUE(mentions(refusal(*leg, spec), "needs a name"));
}

TEST(IkChainBuild, RefusesBadWeights)
{
    const ActorDefinitionPtr leg = makeLegActor();
    IkChainSpec spec = chainSpec("leg", "hip", "ankle", IkSolverType::Dls);
    spec.jointWeights = {{"pelvis", 0.5}};
    EXPECT_TRUE(mentions(refusal(*leg, spec), "joint weight names 'pelvis', not a joint of the chain"));
    spec.jointWeights = {{"knee", -1.0}};
    EXPECT_TRUE(mentions(refusal(*leg, spec), "weights must be finite and >= 0"));
    spec.jointWeights = {{"knee", std::numeric_limits<double>::infinity()}};
    EXPECT_TRUE(mentions(refusal(*leg, spec), "weights must be finite and >= 0"));
    spec.jointWeights.clear();
    spec.dofWeights = {{"pelvis.rx", 0.5}};
    EXPECT_TRUE(mentions(refusal(*leg, spec), "DOF weight names 'pelvis.rx', not a DOF of the chain"));
    spec.dofWeights = {{"knee.ry", 0.5}}; // the knee has rx only
    EXPECT_TRUE(mentions(refusal(*leg, spec), "'knee.ry', not a DOF of the chain"));
    spec.dofWeights = {{"knee.rx", std::numeric_limits<double>::quiet_NaN()}};
    EXPECT_TRUE(mentions(refusal(*leg, spec), "weights must be finite and >= 0"));
    // Nothing left to drive.
    spec.dofWeights.clear();
    spec.jointWeights = {{"hip", 0.0}, {"knee", 0.0}, {"ankle", 0.0}};
    EXPECT_TRUE(mentions(refusal(*leg, spec), "no DOF to drive"));
}

TEST(IkChainBuild, RefusesATwoBoneChainThatIsNotALimb)
{
    const ActorDefinitionPtr leg = makeLegActor();
    // Four joints.
    EXPECT_TRUE(
        mentions(refusal(*leg, chainSpec("c", "pelvis", "ankle", IkSolverType::TwoBone)), "two-bone solver needs"));
    // Two driven DOFs on the middle joint.
    const ActorDefinitionPtr arm = makeArmActor();
    EXPECT_TRUE(
        mentions(refusal(*arm, chainSpec("c", "chest", "wrist", IkSolverType::TwoBone)), "two-bone solver needs"));
    // A root without a driven rotation.
    IkChainSpec spec = chainSpec("leg", "hip", "ankle", IkSolverType::TwoBone);
    spec.jointWeights = {{"hip", 0.0}};
    EXPECT_TRUE(mentions(refusal(*leg, spec), "two-bone solver needs"));
    // Weight 0 on the others picks the bend on a 3-DOF middle joint.
    IkChainSpec shoulderToHand = chainSpec("c", "shoulder", "hand", IkSolverType::TwoBone);
    EXPECT_TRUE(mentions(refusal(*arm, shoulderToHand), "two-bone solver needs")) << "the wrist has three DOFs";
    shoulderToHand.rootJoint = "chest";
    shoulderToHand.effectorJoint = "elbow";
    EXPECT_FALSE(buildIkChain(*arm, shoulderToHand)) << "the chest has no DOF";
}

TEST(IkChainBuild, ListsJointsDofsLengthAndWeights)
{
    const ActorDefinitionPtr leg = makeLegActor();
    IkChainSpec spec = chainSpec("l_leg", "hip", "ankle", IkSolverType::TwoBone, glm::dvec3(0, -0.05, 0.12));
    spec.jointWeights = {{"ankle", 0.5}};
    spec.dofWeights = {{"hip.rz", 0.0}, {"hip.ry", 4.0}};
    const IkChainBuildResult result = buildIkChain(*leg, spec);
    ASSERT_TRUE(result) << result.error;
    const IkChain& chain = *result.chain;
    EXPECT_EQ(chain.getName(), "l_leg");
    EXPECT_EQ(chain.getSolver(), IkSolverType::TwoBone);
    EXPECT_EQ(chain.getMaxIterations(), kDefaultIkIterations);
    EXPECT_EQ(chain.getTolerance(), kDefaultIkTolerance);
    EXPECT_EQ(chain.getJoints(), (std::vector<unsigned>{1, 2, 3}));
    EXPECT_EQ(chain.getRootJoint(), 1u);
    EXPECT_EQ(chain.getEffectorJoint(), 3u);
    // hip.rx, hip.ry (hip.rz frozen), knee.rx, ankle.rx/ry/rz; heaviest (hip.ry, 4) scaled to 1.
    ASSERT_EQ(chain.getNumDofs(), 6u);
    const std::vector<std::string> names{"hip.rx", "hip.ry", "knee.rx", "ankle.rx", "ankle.ry", "ankle.rz"};
    const std::vector<double> weights{0.25, 1.0, 0.25, 0.125, 0.125, 0.125};
    for (unsigned d = 0; d < 6; ++d)
    {
        EXPECT_EQ(leg->getDofName(chain.getDof(d).dof), names[d]);
        EXPECT_DOUBLE_EQ(chain.getDof(d).weight, weights[d]) << names[d];
        EXPECT_EQ(chain.getDof(d).min, leg->getDofMin(chain.getDof(d).dof));
        EXPECT_EQ(chain.getDof(d).max, leg->getDofMax(chain.getDof(d).dof));
    }
    EXPECT_EQ(chain.getDof(1).rotationSlot, 1u) << "ry is the second rotation of an XYZ joint";
    EXPECT_EQ(chain.getFirstJointDof(0), 0u);
    EXPECT_EQ(chain.getFirstJointDof(1), 2u);
    EXPECT_EQ(chain.getFirstJointDof(2), 3u);
    EXPECT_EQ(chain.getFirstJointDof(3), 6u);
    EXPECT_TRUE(chain.isTwoBoneLayout());
    EXPECT_EQ(chain.getTwoBoneBendDof(), 2);
    // Bones knee (0, -0.45, 0.02) and ankle (0, -0.42, -0.01), then the effector offset (0, -0.05, 0.12).
    const double length = std::sqrt(0.45 * 0.45 + 0.02 * 0.02) + std::sqrt(0.42 * 0.42 + 0.01 * 0.01) +
                          std::sqrt(0.05 * 0.05 + 0.12 * 0.12);
    EXPECT_NEAR(chain.getLength(), length, 1e-15);
    EXPECT_TRUE(chain.fits(*leg));
    EXPECT_FALSE(chain.fits(*makeArmActor()));
    // The description is kept as given, names and all, for writing back.
    EXPECT_EQ(chain.getSpec().dofWeights.size(), 2u);
    EXPECT_EQ(chain.getSpec().effectorOffset, glm::dvec3(0, -0.05, 0.12));
}

TEST(IkChainBuild, UsesTheDefinitionsDofWeights)
{
    ActorDefinitionBuilder b("weighted");
    b.addJoint("a").dofs(Dof::RX | Dof::RY).weight(Dof::RX, 2.0).weight(Dof::RY, 0.0);
    b.addJoint("b", "a").offset(1, 0, 0).dofs(dofBit(Dof::RZ)).weight(Dof::RZ, 0.5);
    const ActorDefinitionPtr definition = b.build().definition;
    const IkChainPtr chain = makeChain(*definition, chainSpec("c", "a", "b", IkSolverType::Ccd));
    ASSERT_EQ(chain->getNumDofs(), 2u) << "a.ry has weight 0 in the definition";
    EXPECT_EQ(chain->getDof(0).weight, 1.0);
    EXPECT_EQ(chain->getDof(1).weight, 0.25);
    EXPECT_FALSE(chain->isTwoBoneLayout());
}

TEST(IkSolverNames, RoundTrip)
{
    for (IkSolverType solver : {IkSolverType::TwoBone, IkSolverType::Ccd, IkSolverType::Dls})
    {
        IkSolverType parsed = IkSolverType::Dls;
        EXPECT_TRUE(parseIkSolver(ikSolverName(solver), parsed));
        EXPECT_EQ(parsed, solver);
    }
    IkSolverType parsed = IkSolverType::Ccd;
    EXPECT_TRUE(parseIkSolver("TwoBone", parsed));
    EXPECT_EQ(parsed, IkSolverType::TwoBone);
    EXPECT_FALSE(parseIkSolver("fabrik", parsed));
    EXPECT_EQ(std::string(ikSolverName(IkSolverType::Dls)), "dls");
}
