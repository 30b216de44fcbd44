// The three solvers against targets made by forward kinematics: reach, limits, weights, orientation, bad input.
#include "IkTestUtil"

#include <osgActor/core/ik/CcdIkJob>
#include <osgActor/core/ik/DlsIkJob>
#include <osgActor/core/ik/IkSolve>
#include <osgActor/core/ik/TwoBoneIkJob>

#include <glm/geometric.hpp>

#include <iomanip>
#include <iostream>
#include <limits>

using namespace osgActor;
using namespace osgActor::test;

namespace {

constexpr unsigned kNumTargets = 1000;
constexpr double kReachTolerance = 1e-4; // of the chain's length; radians for orientations

struct RandomTargetReport
{
    unsigned targets = 0;
    unsigned reached = 0;
    double meanIterations = 0.0;
    unsigned maxIterations = 0;
    double worstPositionError = 0.0; // fraction of the chain's length
    unsigned worse = 0;              // solves that ended farther from the goal than they started
    double rate() const { return targets ? double(reached) / targets : 0.0; }
};

/** Solves for numTargets targets, each the effector of a random pose within limits, starting every solve from the
  * rest pose; checks each solution by the actor's own FK, and that it is finite and within limits. */
RandomTargetReport solveRandomTargets(const char* label, const ActorDefinitionPtr& definition, const IkChainPtr& chain,
                                      bool withOrientation, bool withPole, unsigned seed = 20021,
                                      unsigned numTargets = kNumTargets)
{
    RandomTargetReport report;
    std::mt19937 random(seed);
    IkWorkspace workspace;
    workspace.resize(*chain);
    const double length = chain->getLength();
    for (unsigned i = 0; i < numTargets; ++i)
    {
        const std::vector<double> target = randomPose(*definition, random);
        std::vector<double> dofs = target; // joints outside the chain stay as the target has them
        for (const IkChainDof& d : chain->getDofs()) dofs[d.dof] = definition->getDofDefault(d.dof);

        IkGoal goal;
        goal.position = effectorPoint(definition, *chain, target);
        goal.hasOrientation = withOrientation;
        if (withOrientation) goal.orientation = effectorOrientation(definition, *chain, target);
        goal.hasPole = withPole;
        if (withPole) goal.pole = glm::dvec3(modelMatrices(definition, target)[chain->getJoint(1)][3]);

        auto combinedError = [&](const std::vector<double>& pose) {
            const double position = glm::length(effectorPoint(definition, *chain, pose) - goal.position) / length;
            return position + (withOrientation
                                   ? angleBetween(effectorOrientation(definition, *chain, pose), goal.orientation)
                                   : 0.0);
        };
        const double startError = combinedError(dofs);
        IkJob job = makeIkJob(*definition, *chain, goal, dofs, workspace);
        job.rootParentModel = rootParentModel(definition, *chain, dofs);
        // Every other solve starts from the actor's model matrices rather than computing the chain's own.
        const std::vector<glm::dmat4> startModels = modelMatrices(definition, dofs);
        if (i % 2) job.jointModels = startModels.data();
        EXPECT_TRUE(solveIk(job));
        EXPECT_TRUE(withinLimits(*definition, dofs)) << "target " << i;
        if (combinedError(dofs) > startError + 1e-12) ++report.worse;

        const double positionError = glm::length(effectorPoint(definition, *chain, dofs) - goal.position) / length;
        const double angleError =
            withOrientation ? angleBetween(effectorOrientation(definition, *chain, dofs), goal.orientation) : 0.0;
        EXPECT_TRUE(std::isfinite(positionError) && std::isfinite(angleError)) << "target " << i;
        ++report.targets;
        if (positionError <= kReachTolerance && angleError <= kReachTolerance) ++report.reached;
        report.meanIterations += job.result.iterations;
        report.maxIterations = std::max(report.maxIterations, job.result.iterations);
        report.worstPositionError = std::max(report.worstPositionError, positionError);
    }
    report.meanIterations /= report.targets;
    std::cout << "[   IK     ] " << label << ": " << report.reached << "/" << report.targets << " reached ("
              << std::fixed << std::setprecision(1) << 100.0 * report.rate() << "%), iterations mean "
              << std::setprecision(2) << report.meanIterations << " max " << report.maxIterations
              << ", worst position error " << std::scientific << std::setprecision(2) << report.worstPositionError
              << " of the chain's length" << std::defaultfloat << ", " << report.worse
              << " ended worse than they started"
              << std::endl;
    return report;
}

/** Runs one solve of the chain's own solver from the given DOFs; returns the job for its result. */
IkJob solveOnce(const ActorDefinitionPtr& definition, const IkChainPtr& chain, const IkGoal& goal,
                std::vector<double>& dofs, IkWorkspace& workspace)
{
    workspace.resize(*chain);
    IkJob job = makeIkJob(*definition, *chain, goal, dofs, workspace);
    job.rootParentModel = rootParentModel(definition, *chain, dofs);
    EXPECT_TRUE(solveIk(job));
    return job;
}

IkChainPtr legChain(const ActorDefinitionPtr& leg, IkSolverType solver, const glm::dvec3& offset = glm::dvec3(0.0))
{
    return makeChain(*leg, chainSpec("leg", "hip", "ankle", solver, offset));
}

IkChainPtr snakeChain(const ActorDefinitionPtr& snake, IkSolverType solver)
{
    IkChainSpec spec = chainSpec("snake", "s0", "s6", solver, glm::dvec3(0.2, 0, 0));
    spec.maxIterations = 200;
    return makeChain(*snake, spec);
}

IkChainPtr armChain(const ActorDefinitionPtr& arm, IkSolverType solver)
{
    IkChainSpec spec = chainSpec("arm", "shoulder", "wrist", solver, glm::dvec3(0.08, 0, 0));
    spec.maxIterations = 300;
    return makeChain(*arm, spec);
}

} // namespace

// --- invalid inputs first ---

TEST(IkJobs, RefuseMissingOrInvalidInputsAndTouchNothing)
{
    const ActorDefinitionPtr leg = makeLegActor();
    const IkChainPtr chain = legChain(leg, IkSolverType::TwoBone);
    const IkChainPtr other = makeChain(*leg, chainSpec("body", "pelvis", "ankle", IkSolverType::Dls));
    std::vector<double> dofs = leg->getDefaultDofs();
    const std::vector<double> before = dofs;
    IkWorkspace workspace;
    workspace.resize(*chain);
    IkGoal goal;
    goal.position = glm::dvec3(0.1, 0.3, 0.2);

    auto makeJob = [&]() { return makeIkJob(*leg, *chain, goal, dofs, workspace); };
    auto expectRefused = [&](IkJob job, const char* why) {
        TwoBoneIkJob twoBone;
        static_cast<IkJob&>(twoBone) = job;
        CcdIkJob ccd;
        static_cast<IkJob&>(ccd) = job;
        DlsIkJob dls;
        static_cast<IkJob&>(dls) = job;
        EXPECT_FALSE(twoBone.run()) << why;
        EXPECT_FALSE(ccd.run()) << why;
        EXPECT_FALSE(dls.run()) << why;
        EXPECT_FALSE(solveIk(job)) << why;
        EXPECT_EQ(dofs, before) << why;
    };
    { IkJob job = makeJob(); job.definition = nullptr; expectRefused(job, "no definition"); }
    { IkJob job = makeJob(); job.chain = nullptr; expectRefused(job, "no chain"); }
    { IkJob job = makeJob(); job.goal = nullptr; expectRefused(job, "no goal"); }
    { IkJob job = makeJob(); job.dofs = nullptr; expectRefused(job, "no DOFs"); }
    { IkJob job = makeJob(); job.workspace = nullptr; expectRefused(job, "no workspace"); }
    {
        IkWorkspace wrong;
        wrong.resize(*other);
        IkJob job = makeJob();
        job.workspace = &wrong;
        expectRefused(job, "a workspace sized for another chain");
    }
    {
        IkGoal nan = goal;
        nan.position.y = std::numeric_limits<double>::quiet_NaN();
        IkJob job = makeJob();
        job.goal = &nan;
        expectRefused(job, "a NaN goal");
        IkGoal zeroOrientation = goal;
        zeroOrientation.hasOrientation = true;
        zeroOrientation.orientation = glm::dquat(0, 0, 0, 0);
        job.goal = &zeroOrientation;
        expectRefused(job, "a zero orientation");
        IkGoal nanPole = goal;
        nanPole.hasPole = true;
        nanPole.pole.x = std::numeric_limits<double>::infinity();
        job.goal = &nanPole;
        expectRefused(job, "an infinite pole");
    }
    {
        IkJob job = makeJob();
        job.rootParentModel[3][0] = std::numeric_limits<double>::quiet_NaN();
        expectRefused(job, "a NaN root parent matrix");
    }
    {
        std::vector<double> nanDofs = before;
        nanDofs[static_cast<unsigned>(leg->findDof("knee.rx"))] = std::numeric_limits<double>::quiet_NaN();
        IkJob job = makeJob();
        job.dofs = nanDofs.data();
        TwoBoneIkJob twoBone;
        static_cast<IkJob&>(twoBone) = job;
        EXPECT_FALSE(twoBone.run()) << "a NaN chain DOF";
    }
    {
        // A chain built for another actor (the snake) does not fit the leg's DOF vector.
        const ActorDefinitionPtr snake = makeSnakeActor();
        const IkChainPtr snakeChainPtr = snakeChain(snake, IkSolverType::Dls);
        IkWorkspace snakeWorkspace;
        snakeWorkspace.resize(*snakeChainPtr);
        IkJob job = makeJob();
        job.chain = snakeChainPtr.get();
        job.workspace = &snakeWorkspace;
        expectRefused(job, "a chain of another actor");
    }
    {
        // The two-bone job refuses a chain that is not a limb; the general solvers take it.
        IkWorkspace otherWorkspace;
        otherWorkspace.resize(*other);
        IkJob job = makeJob();
        job.chain = other.get();
        job.workspace = &otherWorkspace;
        TwoBoneIkJob twoBone;
        static_cast<IkJob&>(twoBone) = job;
        EXPECT_FALSE(twoBone.validate());
        EXPECT_FALSE(twoBone.run());
        DlsIkJob dls;
        static_cast<IkJob&>(dls) = job;
        EXPECT_TRUE(dls.validate());
    }
}

// --- reaching targets made by forward kinematics ---

TEST(TwoBoneIk, ReachesRandomTargetsWithAPole)
{
    const ActorDefinitionPtr leg = makeLegActor();
    const RandomTargetReport report =
        solveRandomTargets("twobone leg, pole", leg, legChain(leg, IkSolverType::TwoBone), false, true);
    EXPECT_GE(report.rate(), 0.99);
}

TEST(TwoBoneIk, ReachesRandomTargetsWithAnotherHipOrder)
{
    const ActorDefinitionPtr leg = makeLegActor(EulerOrder::ZXY);
    const RandomTargetReport report =
        solveRandomTargets("twobone leg ZXY hip, pole", leg, legChain(leg, IkSolverType::TwoBone), false, true);
    EXPECT_GE(report.rate(), 0.99);
}

TEST(TwoBoneIk, ReachesRandomTargetsWithOrientationAndEffectorOffset)
{
    const ActorDefinitionPtr leg = makeLegActor();
    const IkChainPtr chain = legChain(leg, IkSolverType::TwoBone, glm::dvec3(0, -0.05, 0.12));
    const RandomTargetReport report =
        solveRandomTargets("twobone leg to toe, pole + orientation", leg, chain, true, true);
    EXPECT_GE(report.rate(), 0.99);
}

// The closed form works in the limb's own frames; this limb uses every layout option it must get right: offsets with
// rotations, Euler orders other than XYZ, slides after and before rotation (held: weight 0), a three-rotation middle
// joint whose hinge is its middle slot (the other two held), an effector offset.
TEST(TwoBoneIk, ReachesRandomTargetsOnAnyJointLayout)
{
    ActorDefinitionBuilder b("layouts");
    b.addJoint("base").offset(0.1, 0.9, -0.2).rotation(0.7, 1, 0.3, -0.2).dofs(kRotationDofs);
    b.addJoint("shoulder", "base").offset(0.2, 0.1, 0.05).rotation(-0.4, 0.2, 1, 0).dofs(kRotationDofs | Dof::TX)
        .eulerOrder(EulerOrder::YZX).limits(Dof::RX, -2.0, 2.0).limits(Dof::RY, -1.2, 1.2).limits(Dof::RZ, -1.5, 2.0)
        .limits(Dof::TX, -0.05, 0.05);
    b.addJoint("elbow", "shoulder").offset(0.35, 0.02, -0.03).rotation(0.3, 0, 0, 1).dofs(kRotationDofs | Dof::TZ)
        .eulerOrder(EulerOrder::ZYX).translationMode(TranslationMode::BeforeRotation).limits(Dof::RX, -0.3, 0.3)
        .limits(Dof::RY, 0.0, 2.6).limits(Dof::RZ, -0.3, 0.3).limits(Dof::TZ, -0.04, 0.04);
    b.addJoint("wrist", "elbow").offset(0.3, -0.01, 0.02).rotation(-0.2, 1, 0, 0).dofs(kRotationDofs | Dof::TY)
        .eulerOrder(EulerOrder::XZY).limits(Dof::RX, -1.5, 1.5).limits(Dof::RY, -0.6, 0.6).limits(Dof::RZ, -1.2, 1.2)
        .limits(Dof::TY, -0.03, 0.03);
    const BuildResult built = b.build();
    ASSERT_TRUE(built) << built.error;
    IkChainSpec spec = chainSpec("arm", "shoulder", "wrist", IkSolverType::TwoBone, glm::dvec3(0.06, 0.02, -0.01));
    spec.dofWeights = {{"shoulder.tx", 0.0}, {"elbow.rx", 0.0}, {"elbow.rz", 0.0}, {"elbow.tz", 0.0},
                       {"wrist.ty", 0.0}};
    const IkChainPtr chain = makeChain(*built.definition, spec);
    ASSERT_TRUE(chain->isTwoBoneLayout());
    EXPECT_GE(
        solveRandomTargets("twobone, every layout, pole + orientation", built.definition, chain, true, true).rate(),
        0.99);
    // Without an orientation goal the effector's rotations are held (they only carry the offset), so here they are
    // held where each target has them.
    spec.dofWeights.insert(spec.dofWeights.end(), {{"wrist.rx", 0.0}, {"wrist.ry", 0.0}, {"wrist.rz", 0.0}});
    const IkChainPtr heldWrist = makeChain(*built.definition, spec);
    EXPECT_GE(solveRandomTargets("twobone, every layout, pole", built.definition, heldWrist, false, true).rate(), 0.99);
}

// Without a pole the limb turns by the shortest arc, keeping its bend plane, so a goal may need a root rotation past
// the limits; the general rounds (damped least squares from the analytic start) then finish.
TEST(TwoBoneIk, ReachesRandomTargetsWithoutAPole)
{
    const ActorDefinitionPtr leg = makeLegActor();
    const RandomTargetReport report =
        solveRandomTargets("twobone leg, no pole", leg, legChain(leg, IkSolverType::TwoBone), false, false);
    EXPECT_GE(report.rate(), 0.99);
}

TEST(CcdIk, ReachesRandomTargetsOnASevenJointChain)
{
    const ActorDefinitionPtr snake = makeSnakeActor();
    const RandomTargetReport report =
        solveRandomTargets("ccd snake (7 joints)", snake, snakeChain(snake, IkSolverType::Ccd), false, false);
    EXPECT_GE(report.rate(), 0.99);
}

// CCD turns one DOF at a time, so on a limb, where the hip and the knee must move together to change the reach, its
// plain sweeps have a long slow tail; the sweep acceleration (Anderson mixing, pattern moves) takes it in.
TEST(CcdIk, ReachesRandomTargetsOnALeg)
{
    const ActorDefinitionPtr leg = makeLegActor();
    IkChainSpec spec = chainSpec("leg", "hip", "ankle", IkSolverType::Ccd);
    spec.maxIterations = 200;
    const RandomTargetReport report =
        solveRandomTargets("ccd leg (3 joints)", leg, makeChain(*leg, spec), false, false);
    EXPECT_GE(report.rate(), 0.99);
}

TEST(DlsIk, ReachesRandomTargetsOnASevenJointChain)
{
    const ActorDefinitionPtr snake = makeSnakeActor();
    const RandomTargetReport report =
        solveRandomTargets("dls snake (7 joints)", snake, snakeChain(snake, IkSolverType::Dls), false, false);
    EXPECT_GE(report.rate(), 0.99);
}

TEST(DlsIk, ReachesRandomTargetsOnASevenDofArm)
{
    const ActorDefinitionPtr arm = makeArmActor();
    const RandomTargetReport report =
        solveRandomTargets("dls arm (7 DOFs)", arm, armChain(arm, IkSolverType::Dls), false, false);
    EXPECT_GE(report.rate(), 0.99);
}

TEST(DlsIk, MeetsRandomOrientationGoalsOnASevenDofArm)
{
    const ActorDefinitionPtr arm = makeArmActor();
    const RandomTargetReport report =
        solveRandomTargets("dls arm (7 DOFs), orientation", arm, armChain(arm, IkSolverType::Dls), true, false);
    EXPECT_GE(report.rate(), 0.99);
}

// CCD balances orientation against position one DOF at a time. Every goal here is reachable (the effector frame of
// a pose within the limits), but the limits leave local minima that a pose of the arm can fall into from the rest
// pose and that several restarts fall back into, so CCD, like DLS, needs its restarts and some targets more sweeps
// than the chain's 300. It must never end worse than it started.
TEST(CcdIk, MeetsRandomOrientationGoalsOnASevenDofArm)
{
    const ActorDefinitionPtr arm = makeArmActor();
    const RandomTargetReport report = solveRandomTargets("ccd arm (7 DOFs), orientation", arm,
                                                         armChain(arm, IkSolverType::Ccd), true, false);
    EXPECT_EQ(report.worse, 0u);
    EXPECT_GE(report.rate(), 0.97)
        << "a regression guard: 99.0% when written (43.5% of 200 before the sweep acceleration)";
}

TEST(IkSolvers, NeverEndWorseThanTheyStart)
{
    const ActorDefinitionPtr snake = makeSnakeActor();
    for (IkSolverType solver : {IkSolverType::Ccd, IkSolverType::Dls})
        EXPECT_EQ(solveRandomTargets(ikSolverName(solver), snake, snakeChain(snake, solver), false, false, 7).worse,
                  0u);
}

// --- goals out of reach ---

TEST(TwoBoneIk, StretchesStraightestTowardAGoalOutOfReach)
{
    const ActorDefinitionPtr leg = makeLegActor();
    const IkChainPtr chain = legChain(leg, IkSolverType::TwoBone);
    std::vector<double> dofs = leg->getDefaultDofs();
    const glm::dvec3 hipPivot(modelMatrices(leg, dofs)[chain->getRootJoint()][3]);
    const glm::dvec3 direction = glm::normalize(glm::dvec3(0.2, -1.0, 0.3));
    IkGoal goal;
    goal.position = hipPivot + 5.0 * direction;

    // Independently: the longest hip-to-ankle distance the knee's limits allow, by sampling the knee angle.
    double longest = 0.0;
    for (int i = 0; i <= 26000; ++i)
    {
        std::vector<double> probe = dofs;
        probe[static_cast<unsigned>(leg->findDof("knee.rx"))] = i * 1e-4;
        longest = std::max(longest, glm::length(effectorPoint(leg, *chain, probe) - hipPivot));
    }

    IkWorkspace workspace;
    const IkJob job = solveOnce(leg, chain, goal, dofs, workspace);
    EXPECT_FALSE(job.result.reached);
    EXPECT_TRUE(withinLimits(*leg, dofs));
    const glm::dvec3 effector = effectorPoint(leg, *chain, dofs);
    EXPECT_NEAR(glm::length(goal.position - effector), 5.0 - longest, 1e-7) << "as close as the limits allow";
    const glm::dvec3 alongLine = hipPivot + direction * glm::dot(effector - hipPivot, direction);
    EXPECT_LT(glm::length(effector - alongLine), 1e-9) << "on the line from the hip to the goal";
    EXPECT_NEAR(job.result.positionError, 5.0 - longest, 1e-7);
}

TEST(IkSolvers, StretchStraightTowardAGoalOutOfReach)
{
    const ActorDefinitionPtr snake = makeSnakeActor();
    for (IkSolverType solver : {IkSolverType::Ccd, IkSolverType::Dls})
    {
        const IkChainPtr chain = snakeChain(snake, solver);
        std::vector<double> dofs = snake->getDefaultDofs();
        dofs[2] = 0.7; // start bent
        dofs[5] = -0.9;
        IkGoal goal;
        // In s0's plane (s1's pitch sits 0.2 along the first bone, so only there can the whole chain line up with
        // s0's pivot, the origin, and the goal).
        goal.position = 3.0 * glm::normalize(glm::dvec3(1.0, 0.5, 0.0));
        IkWorkspace workspace;
        const IkJob job = solveOnce(snake, chain, goal, dofs, workspace);
        EXPECT_FALSE(job.result.reached) << ikSolverName(solver);
        EXPECT_TRUE(withinLimits(*snake, dofs)) << ikSolverName(solver);
        // Fully stretched (1.4 long) along the line to the goal.
        const double distance = glm::length(goal.position - effectorPoint(snake, *chain, dofs));
        EXPECT_NEAR(distance, 3.0 - 1.4, 1e-3 * chain->getLength()) << ikSolverName(solver);
    }
}

TEST(IkSolvers, NeverLeaveTheLimitsNorWriteNaN)
{
    // Goals anywhere in a box three chain lengths wide, most out of reach or only reachable past the limits.
    const ActorDefinitionPtr leg = makeLegActor();
    std::mt19937 random(5);
    std::uniform_real_distribution<double> coordinate(-2.6, 2.6);
    for (IkSolverType solver : {IkSolverType::TwoBone, IkSolverType::Ccd, IkSolverType::Dls})
    {
        const IkChainPtr chain = legChain(leg, solver, glm::dvec3(0, -0.05, 0.12));
        IkWorkspace workspace;
        for (int i = 0; i < 200; ++i)
        {
            std::vector<double> dofs = randomPose(*leg, random);
            IkGoal goal;
            goal.position = glm::dvec3(coordinate(random), coordinate(random), coordinate(random));
            goal.hasOrientation = i % 2 == 0;
            goal.orientation =
                glm::normalize(glm::dquat(coordinate(random), coordinate(random), coordinate(random), 1.0));
            goal.hasPole = i % 3 == 0;
            goal.pole = glm::dvec3(coordinate(random), coordinate(random), coordinate(random));
            const IkJob job = solveOnce(leg, chain, goal, dofs, workspace);
            ASSERT_TRUE(withinLimits(*leg, dofs)) << ikSolverName(solver) << " goal " << i;
            ASSERT_TRUE(std::isfinite(job.result.positionError) && std::isfinite(job.result.orientationError));
        }
    }
}

// --- weights ---

TEST(IkSolvers, AZeroJointWeightFreezesTheJoint)
{
    const ActorDefinitionPtr snake = makeSnakeActor();
    const unsigned frozenDof = static_cast<unsigned>(snake->findDof("s2.rz"));
    for (IkSolverType solver : {IkSolverType::Ccd, IkSolverType::Dls})
    {
        IkChainSpec spec = chainSpec("snake", "s0", "s6", solver, glm::dvec3(0.2, 0, 0));
        spec.maxIterations = 200;
        spec.jointWeights = {{"s2", 0.0}};
        const IkChainPtr chain = makeChain(*snake, spec);
        ASSERT_EQ(chain->getNumDofs(), 6u);
        std::mt19937 random(11);
        unsigned reached = 0;
        for (int i = 0; i < 50; ++i)
        {
            std::vector<double> target = randomPose(*snake, random);
            std::vector<double> dofs = snake->getDefaultDofs();
            dofs[frozenDof] = 0.4;
            target[frozenDof] = 0.4; // reachable with the frozen joint where it is
            IkGoal goal;
            goal.position = effectorPoint(snake, *chain, target);
            IkWorkspace workspace;
            solveOnce(snake, chain, goal, dofs, workspace);
            EXPECT_EQ(dofs[frozenDof], 0.4) << ikSolverName(solver);
            if (glm::length(effectorPoint(snake, *chain, dofs) - goal.position) <= 1e-4 * chain->getLength()) ++reached;
        }
        EXPECT_GE(reached, 49u) << ikSolverName(solver);
    }
}

TEST(TwoBoneIk, AZeroDofWeightFreezesTheDofAndTheRestStillReaches)
{
    const ActorDefinitionPtr leg = makeLegActor();
    IkChainSpec spec = chainSpec("leg", "hip", "ankle", IkSolverType::TwoBone);
    spec.dofWeights = {{"hip.rz", 0.0}};
    const IkChainPtr chain = makeChain(*leg, spec);
    const unsigned frozenDof = static_cast<unsigned>(leg->findDof("hip.rz"));
    std::mt19937 random(3);
    unsigned reached = 0;
    for (int i = 0; i < 100; ++i)
    {
        std::vector<double> target = randomPose(*leg, random);
        std::vector<double> dofs = target;
        for (const IkChainDof& d : chain->getDofs()) dofs[d.dof] = 0.0;
        dofs[frozenDof] = target[frozenDof] = 0.25;
        IkGoal goal;
        goal.position = effectorPoint(leg, *chain, target);
        IkWorkspace workspace;
        solveOnce(leg, chain, goal, dofs, workspace);
        EXPECT_EQ(dofs[frozenDof], 0.25);
        if (glm::length(effectorPoint(leg, *chain, dofs) - goal.position) <= 1e-4 * chain->getLength()) ++reached;
    }
    std::cout << "[   IK     ] twobone leg with hip.rz frozen: " << reached << "/100 reached" << std::endl;
    EXPECT_GE(reached, 99u);
}

TEST(DlsIk, HeavierDofsMoveMore)
{
    // Two equal DOFs that both move the effector the same way: the step splits in proportion to their weights.
    ActorDefinitionBuilder b("pair");
    b.addJoint("a").dofs(dofBit(Dof::RZ)).weight(Dof::RZ, 1.0);
    b.addJoint("b", "a").dofs(dofBit(Dof::RZ)).weight(Dof::RZ, 0.25);
    b.addJoint("c", "b").offset(1, 0, 0);
    const BuildResult built = b.build();
    ASSERT_TRUE(built) << built.error;
    // b's pivot at a's: both rotations turn the tip about the same axis through the same point.
    IkChainSpec spec = chainSpec("pair", "a", "c", IkSolverType::Dls);
    const IkChainPtr chain = makeChain(*built.definition, spec);
    std::vector<double> dofs = built.definition->getDefaultDofs();
    IkGoal goal;
    goal.position = glm::dvec3(std::cos(0.5), std::sin(0.5), 0.0);
    IkWorkspace workspace;
    const IkJob job = solveOnce(built.definition, chain, goal, dofs, workspace);
    EXPECT_TRUE(job.result.reached);
    EXPECT_NEAR(dofs[0] + dofs[1], 0.5, 1e-4);
    EXPECT_NEAR(dofs[0] / dofs[1], 4.0, 1e-3) << "weights 1 and 0.25";
}
