// IK as a controller: on top of the controllers before it, through selections and weights, goals in model or
// world space, several chains in the order they were added.
#include "IkTestUtil"
#include "TestMath"

#include <osgActor/core/ik/IkController>

#include <glm/ext/matrix_transform.hpp>
#include <glm/geometric.hpp>

#include <limits>

using namespace osgActor;
using namespace osgActor::test;

namespace {

/** A stand-in for a clip player: writes fixed values to the DOFs it is given. */
class PoseController : public Controller
{
public:
    explicit PoseController(std::vector<std::pair<unsigned, double>> values) : _values(std::move(values)) {}
    void update(const ControllerContext&, ControllerTarget& target) override
    {
        for (const auto& v : _values) writeDof(target.pose, v.first, v.second);
    }
    std::shared_ptr<Controller> cloneController() const override { return std::make_shared<PoseController>(*this); }

private:
    std::vector<std::pair<unsigned, double>> _values;
};

/** The clip's values: every DOF of a random pose. */
std::vector<std::pair<unsigned, double>> allOf(const std::vector<double>& dofs)
{
    std::vector<std::pair<unsigned, double>> values;
    for (unsigned d = 0; d < dofs.size(); ++d) values.emplace_back(d, dofs[d]);
    return values;
}

void run(const std::vector<ControllerPtr>& controllers, ActorPose& pose, const ControllerContext& context = {})
{
    ActorTransforms transforms;
    ControllerTarget target{pose, transforms};
    runControllers(controllers, context, target);
    pose.updateMatrices();
}

glm::dvec3 effectorOf(const ActorPose& pose, const IkChain& chain)
{
    return glm::dvec3(pose.getModelMatrix(chain.getEffectorJoint()) * glm::dvec4(chain.getEffectorOffset(), 1.0));
}

} // namespace

TEST(IkController, RefusesInvalidGoalsAndDoesNothingWithoutOne)
{
    const ActorDefinitionPtr leg = makeLegActor();
    auto ik = std::make_shared<IkController>(makeChain(*leg, chainSpec("leg", "hip", "ankle", IkSolverType::TwoBone)));
    EXPECT_EQ(ik->getName(), "leg");
    IkGoal nan;
    nan.position.x = std::numeric_limits<double>::quiet_NaN();
    EXPECT_FALSE(ik->setGoal(nan));
    EXPECT_FALSE(ik->hasGoal());
    ActorPose pose(leg);
    run({ik}, pose);
    EXPECT_EQ(pose.getDofs(), leg->getDefaultDofs());

    IkGoal goal;
    goal.position = glm::dvec3(0.2, 0.4, 0.1);
    EXPECT_TRUE(ik->setGoal(goal));
    EXPECT_FALSE(ik->setGoal(nan)) << "a refused goal keeps the old one";
    EXPECT_EQ(ik->getGoal().position, goal.position);
    ik->clearGoal();
    run({ik}, pose);
    EXPECT_EQ(pose.getDofs(), leg->getDefaultDofs());

    // A chain built for another actor is ignored.
    const ActorDefinitionPtr snake = makeSnakeActor();
    auto foreign = std::make_shared<IkController>(makeChain(*snake, chainSpec("s", "s0", "s6", IkSolverType::Dls)));
    foreign->setGoal(goal);
    run({foreign}, pose);
    EXPECT_EQ(pose.getDofs(), leg->getDefaultDofs());
}

TEST(IkController, SolvesOnTopOfTheControllersBeforeIt)
{
    const ActorDefinitionPtr leg = makeLegActor();
    const IkChainPtr chain = makeChain(*leg, chainSpec("leg", "hip", "ankle", IkSolverType::TwoBone));
    std::mt19937 random(8);
    const std::vector<double> clip = randomPose(*leg, random);   // what the clip plays this frame
    std::vector<double> planted = randomPose(*leg, random);      // where IK should put the foot
    for (unsigned d = 0; d < 3; ++d) planted[d] = clip[d];       // the pelvis as the clip has it
    IkGoal goal;
    goal.position = effectorPoint(leg, *chain, planted);
    goal.pole = glm::dvec3(modelMatrices(leg, planted)[chain->getJoint(1)][3]);
    goal.hasPole = true;

    auto player = std::make_shared<PoseController>(allOf(clip));
    auto ik = std::make_shared<IkController>(chain);
    ik->setGoal(goal);
    ActorPose pose(leg);
    run({player, ik}, pose);
    EXPECT_TRUE(vectorsNear(effectorOf(pose, *chain), goal.position, 1e-4 * chain->getLength()));
    EXPECT_TRUE(ik->getLastResult().reached);
    for (unsigned d = 0; d < 3; ++d) EXPECT_EQ(pose.getDof(d), clip[d]) << "the pelvis stays the clip's";
    const unsigned ankle = static_cast<unsigned>(leg->findDof("ankle.rx"));
    EXPECT_EQ(pose.getDof(ankle), clip[ankle]) << "no orientation goal: the ankle keeps the clip's rotation";
}

TEST(IkController, LeavesDofsOutsideItsSelectionAndBlendsByWeight)
{
    const ActorDefinitionPtr leg = makeLegActor();
    const IkChainPtr chain = makeChain(*leg, chainSpec("leg", "hip", "ankle", IkSolverType::Dls));
    std::mt19937 random(9);
    const std::vector<double> clip = randomPose(*leg, random);
    std::vector<double> planted = randomPose(*leg, random);
    const unsigned hipRz = static_cast<unsigned>(leg->findDof("hip.rz"));
    for (unsigned d = 0; d < 3; ++d) planted[d] = clip[d];
    planted[hipRz] = clip[hipRz];
    IkGoal goal;
    goal.position = effectorPoint(leg, *chain, planted);

    // Everything of the leg but hip.rz: the solve holds hip.rz where the clip put it and still reaches.
    DofSelection selection = DofSelection::joints(*leg, {"hip"}, true);
    selection.setWeight(leg->getNumDofs(), hipRz, 0.0);
    auto ik = std::make_shared<IkController>(chain);
    ik->setSelection(selection);
    ik->setGoal(goal);
    ActorPose pose(leg);
    run({std::make_shared<PoseController>(allOf(clip)), ik}, pose);
    EXPECT_EQ(pose.getDof(hipRz), clip[hipRz]);
    EXPECT_TRUE(vectorsNear(effectorOf(pose, *chain), goal.position, 1e-4 * chain->getLength()));

    // At weight 0.5 every chain DOF lands halfway between the clip's value and the full solution.
    const std::vector<double> solved = pose.getDofs();
    ik->setWeight(0.5);
    ActorPose blended(leg);
    run({std::make_shared<PoseController>(allOf(clip)), ik}, blended);
    for (const IkChainDof& d : chain->getDofs())
        EXPECT_NEAR(blended.getDof(d.dof), 0.5 * (clip[d.dof] + solved[d.dof]), 1e-9) << leg->getDofName(d.dof);
}

TEST(IkController, ConvertsWorldGoalsWithTheActorsWorldMatrix)
{
    const ActorDefinitionPtr arm = makeArmActor();
    const IkChainPtr chain =
        makeChain(*arm, chainSpec("arm", "shoulder", "wrist", IkSolverType::Dls, glm::dvec3(0.08, 0, 0)));
    std::mt19937 random(10);
    const std::vector<double> target = randomPose(*arm, random);
    const glm::dvec3 modelGoal = effectorPoint(arm, *chain, target);
    const glm::dquat modelOrientation = effectorOrientation(arm, *chain, target);

    ControllerContext context;
    context.parentToWorld = glm::translate(glm::dmat4(1.0), glm::dvec3(5, 0, -2)) *
                            glm::rotate(glm::dmat4(1.0), 1.2, glm::normalize(glm::dvec3(0, 1, 0.2)));
    ActorTransforms transforms;
    transforms.preTranslation = glm::dvec3(1, 2, 3);
    transforms.preRotation = glm::angleAxis(0.5, glm::dvec3(0, 0, 1));
    transforms.postTranslation = glm::dvec3(0, 0.9, 0);
    transforms.postRotation = glm::angleAxis(-0.3, glm::dvec3(1, 0, 0));
    // world = parentToWorld * pretr_m * posttr_m * model, built here from the parts.
    const glm::dmat4 modelToWorld = context.parentToWorld * glm::translate(glm::dmat4(1.0), transforms.preTranslation) *
                                    glm::mat4_cast(transforms.preRotation) *
                                    glm::translate(glm::dmat4(1.0), transforms.postTranslation) *
                                    glm::mat4_cast(transforms.postRotation);
    IkGoal worldGoal;
    worldGoal.position = glm::dvec3(modelToWorld * glm::dvec4(modelGoal, 1.0));
    worldGoal.orientation = glm::quat_cast(glm::dmat3(modelToWorld)) * modelOrientation;
    worldGoal.hasOrientation = true;

    auto ik = std::make_shared<IkController>(chain);
    ik->setGoal(worldGoal, IkGoalSpace::World);
    EXPECT_TRUE(ik->usesWorldSpace());
    ActorPose pose(arm);
    ControllerTarget controllerTarget{pose, transforms};
    runControllers({ik}, context, controllerTarget);
    pose.updateMatrices();
    EXPECT_TRUE(vectorsNear(ik->getLastModelGoal().position, modelGoal, 1e-12));
    EXPECT_TRUE(vectorsNear(effectorOf(pose, *chain), modelGoal, 1e-4 * chain->getLength()));
    EXPECT_LE(angleBetween(glm::quat_cast(glm::dmat3(pose.getModelMatrix(chain->getEffectorJoint()))),
                           modelOrientation),
              1e-4);
}

TEST(IkController, SolvesSeveralChainsInTheOrderAdded)
{
    // The snake's first half, then its second half hanging off the first's end.
    const ActorDefinitionPtr snake = makeSnakeActor();
    const IkChainPtr front = makeChain(*snake, chainSpec("front", "s0", "s3", IkSolverType::Dls));
    const IkChainPtr back = makeChain(*snake, chainSpec("back", "s4", "s6", IkSolverType::Dls, glm::dvec3(0.2, 0, 0)));
    std::mt19937 random(12);
    auto frontIk = std::make_shared<IkController>(front);
    IkGoal frontGoal;
    frontGoal.position = effectorPoint(snake, *front, randomPose(*snake, random));
    frontIk->setGoal(frontGoal);
    // The back chain's goal is reachable from where the front chain's solve leaves its root.
    ActorPose frontOnly(snake);
    run({frontIk}, frontOnly);
    std::vector<double> target = frontOnly.getDofs();
    const std::vector<double> other = randomPose(*snake, random);
    for (const IkChainDof& d : back->getDofs()) target[d.dof] = other[d.dof];
    auto backIk = std::make_shared<IkController>(back);
    IkGoal backGoal;
    backGoal.position = effectorPoint(snake, *back, target);
    backIk->setGoal(backGoal);

    ActorPose inOrder(snake);
    run({frontIk, backIk}, inOrder);
    EXPECT_TRUE(vectorsNear(effectorOf(inOrder, *front), frontGoal.position, 1e-4 * front->getLength()));
    EXPECT_TRUE(vectorsNear(effectorOf(inOrder, *back), backGoal.position, 1e-4 * back->getLength()))
        << "the back chain solved from where the front chain left its root";

    // The other way round the front chain moves the back chain's root after the back chain was solved.
    ActorPose reversed(snake);
    run({backIk, frontIk}, reversed);
    EXPECT_TRUE(vectorsNear(effectorOf(reversed, *front), frontGoal.position, 1e-4 * front->getLength()));
    EXPECT_GT(glm::length(effectorOf(reversed, *back) - backGoal.position), 1e-3);
}

TEST(IkController, ClonesAreIndependent)
{
    const ActorDefinitionPtr leg = makeLegActor();
    auto ik = std::make_shared<IkController>(makeChain(*leg, chainSpec("leg", "hip", "ankle", IkSolverType::TwoBone)));
    IkGoal goal;
    goal.position = glm::dvec3(0.1, 0.3, 0.2);
    ik->setGoal(goal);
    std::shared_ptr<Controller> copy = ik->cloneController();
    auto clone = std::dynamic_pointer_cast<IkController>(copy);
    ASSERT_TRUE(clone);
    EXPECT_EQ(clone->getChain(), ik->getChain()) << "the chain is shared";
    IkGoal other = goal;
    other.position.x = -0.3;
    clone->setGoal(other);
    EXPECT_EQ(ik->getGoal().position.x, 0.1);
}
