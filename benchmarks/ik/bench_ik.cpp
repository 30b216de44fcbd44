// IK solve time per solver and chain length (2, 3 and 7 joints), in microseconds per solve. Each solve starts from
// the rest pose and aims at the effector of a random pose within the limits (fixed seed), so every goal is
// reachable; the counters say how many iterations a solve took and how many reached the tolerance.
#include "IkTestActors"

#include <osgActor/core/ActorPose>
#include <osgActor/core/ik/CcdIkJob>
#include <osgActor/core/ik/DlsIkJob>
#include <osgActor/core/ik/TwoBoneIkJob>

#include <benchmark/benchmark.h>

#include <glm/gtc/quaternion.hpp>

#include <random>
#include <vector>

using namespace osgActor;

namespace {

constexpr unsigned kNumGoals = 256;

/** A chain with its goals and the buffers a solve needs. */
struct Problem
{
    ActorDefinitionPtr definition;
    IkChainPtr chain;
    std::vector<IkGoal> goals;
    std::vector<double> rest;
    glm::dmat4 rootParentModel{1.0};
};

Problem makeProblem(ActorDefinitionPtr definition, const IkChainSpec& spec, bool withOrientation, bool withPole)
{
    Problem problem;
    problem.definition = std::move(definition);
    problem.chain = buildIkChain(*problem.definition, spec).chain;
    problem.rest = problem.definition->getDefaultDofs();
    std::mt19937 random(20021);
    ActorPose pose(problem.definition);
    for (unsigned i = 0; i < kNumGoals; ++i)
    {
        std::vector<double> dofs(problem.rest.size());
        for (unsigned d = 0; d < dofs.size(); ++d)
        {
            const double lo = std::max(problem.definition->getDofMin(d), -3.0);
            const double hi = std::min(problem.definition->getDofMax(d), 3.0);
            dofs[d] = (d < problem.chain->getDof(0).dof) ? problem.rest[d]
                                                         : std::uniform_real_distribution<double>(lo, hi)(random);
        }
        pose.setDofs(dofs.data(), dofs.size());
        pose.updateMatrices();
        const glm::dmat4& effector = pose.getModelMatrix(problem.chain->getEffectorJoint());
        IkGoal goal;
        goal.position = glm::dvec3(effector * glm::dvec4(problem.chain->getEffectorOffset(), 1.0));
        goal.hasOrientation = withOrientation;
        goal.orientation = glm::quat_cast(glm::dmat3(effector));
        goal.hasPole = withPole;
        goal.pole = glm::dvec3(pose.getModelMatrix(problem.chain->getJoint(1))[3]);
        problem.goals.push_back(goal);
    }
    pose.setDofs(problem.rest.data(), problem.rest.size());
    pose.updateMatrices();
    const int parent = problem.definition->getParent(problem.chain->getRootJoint());
    if (parent >= 0) problem.rootParentModel = pose.getModelMatrix(static_cast<unsigned>(parent));
    return problem;
}

/** Solves the problem's goals in turn from its rest pose; with givenModels the job takes the chain's starting
  * frames from the actor's model matrices (as IkController does) rather than computing the chain's FK. */
template <class Solver>
void runSolves(benchmark::State& state, const Problem& problem, bool givenModels = false)
{
    ActorPose restPose(problem.definition);
    restPose.updateMatrices();
    IkWorkspace workspace;
    workspace.resize(*problem.chain);
    std::vector<double> dofs = problem.rest;
    Solver job;
    job.definition = problem.definition.get();
    job.chain = problem.chain.get();
    job.rootParentModel = problem.rootParentModel;
    job.dofs = dofs.data();
    job.workspace = &workspace;
    if (givenModels) job.jointModels = &restPose.getModelMatrix(0);
    unsigned next = 0;
    double iterations = 0.0, reached = 0.0, solves = 0.0;
    for (auto _ : state)
    {
        for (const IkChainDof& d : problem.chain->getDofs()) dofs[d.dof] = problem.rest[d.dof];
        job.goal = &problem.goals[next];
        next = (next + 1) % kNumGoals;
        job.run();
        benchmark::DoNotOptimize(dofs.data());
        iterations += job.result.iterations;
        reached += job.result.reached ? 1.0 : 0.0;
        solves += 1.0;
    }
    state.counters["iterations"] = iterations / solves;
    state.counters["reached"] = reached / solves;
    state.counters["dofs"] = problem.chain->getNumDofs();
}

IkChainSpec spec(const char* root, const char* effector, IkSolverType solver, const glm::dvec3& offset)
{
    IkChainSpec s;
    s.name = "bench";
    s.rootJoint = root;
    s.effectorJoint = effector;
    s.solver = solver;
    s.effectorOffset = offset;
    s.maxIterations = 1000;
    return s;
}

// 2 joints: hip (3 DOFs) and knee (1), the effector at the ankle. 3 joints: hip, knee, ankle (7 DOFs), effector at
// the toe. 7 joints: the snake (7 one-DOF joints).
Problem twoJoints(IkSolverType solver)
{
    return makeProblem(test::makeLegActor(), spec("hip", "knee", solver, glm::dvec3(0, -0.42, -0.01)), false, false);
}
Problem threeJoints(IkSolverType solver, bool withPole)
{
    return makeProblem(test::makeLegActor(), spec("hip", "ankle", solver, glm::dvec3(0, 0, 0)), false, withPole);
}
Problem sevenJoints(IkSolverType solver)
{
    return makeProblem(test::makeSnakeActor(), spec("s0", "s6", solver, glm::dvec3(0.2, 0, 0)), false, false);
}

void BM_TwoBone_3Joints(benchmark::State& state)
{
    runSolves<TwoBoneIkJob>(state, threeJoints(IkSolverType::TwoBone, true));
}
void BM_TwoBone_3Joints_GivenModels(benchmark::State& state)
{
    runSolves<TwoBoneIkJob>(state, threeJoints(IkSolverType::TwoBone, true), true);
}
void BM_TwoBone_3Joints_Orientation(benchmark::State& state)
{
    runSolves<TwoBoneIkJob>(state, makeProblem(test::makeLegActor(),
                                               spec("hip", "ankle", IkSolverType::TwoBone, glm::dvec3(0, -0.05, 0.12)),
                                               true, true));
}
void BM_Ccd_2Joints(benchmark::State& state) { runSolves<CcdIkJob>(state, twoJoints(IkSolverType::Ccd)); }
void BM_Ccd_3Joints(benchmark::State& state) { runSolves<CcdIkJob>(state, threeJoints(IkSolverType::Ccd, false)); }
void BM_Ccd_7Joints(benchmark::State& state) { runSolves<CcdIkJob>(state, sevenJoints(IkSolverType::Ccd)); }
void BM_Dls_2Joints(benchmark::State& state) { runSolves<DlsIkJob>(state, twoJoints(IkSolverType::Dls)); }
void BM_Dls_3Joints(benchmark::State& state) { runSolves<DlsIkJob>(state, threeJoints(IkSolverType::Dls, false)); }
void BM_Dls_7Joints(benchmark::State& state) { runSolves<DlsIkJob>(state, sevenJoints(IkSolverType::Dls)); }
void BM_Dls_7Joints_GivenModels(benchmark::State& state)
{
    runSolves<DlsIkJob>(state, sevenJoints(IkSolverType::Dls), true);
}
void BM_Dls_7DofArm_Orientation(benchmark::State& state)
{
    runSolves<DlsIkJob>(state, makeProblem(test::makeArmActor(),
                                           spec("shoulder", "wrist", IkSolverType::Dls, glm::dvec3(0.08, 0, 0)), true,
                                           false));
}

void BM_Ccd_7DofArm_Orientation(benchmark::State& state)
{
    IkChainSpec arm = spec("shoulder", "wrist", IkSolverType::Ccd, glm::dvec3(0.08, 0, 0));
    arm.maxIterations = 300; // as the tests give it
    runSolves<CcdIkJob>(state, makeProblem(test::makeArmActor(), arm, true, false));
}

BENCHMARK(BM_TwoBone_3Joints)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_TwoBone_3Joints_GivenModels)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_TwoBone_3Joints_Orientation)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Ccd_2Joints)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Ccd_3Joints)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Ccd_7Joints)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Dls_2Joints)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Dls_3Joints)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Dls_7Joints)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Dls_7Joints_GivenModels)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Dls_7DofArm_Orientation)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Ccd_7DofArm_Orientation)->Unit(benchmark::kMicrosecond);

} // namespace

BENCHMARK_MAIN();
