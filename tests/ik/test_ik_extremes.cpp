// Goals and poses near the end of the double range (found by the soak test, docs/robustness.md): finite inputs whose
// products overflow. Every solver must still leave every DOF finite and within its range, never report a NaN error,
// and touch nothing when it gives up; a start pose beyond what a pose can hold (kMaxDofMagnitude) is refused.
#include "IkTestUtil"

#include <osgActor/core/ik/IkSolve>

#include <cmath>
#include <limits>
#include <string>

using namespace osgActor;
using namespace osgActor::test;

namespace {

const double kMax = std::numeric_limits<double>::max(); // 1.797e308

/** A walker: "pelvis" free in space (three translations and three rotations without limits, like a humanoid's root),
  * then a limited leg "hip" (rx ry rz), "knee" (rx), "ankle" (rx), "toe" (no DOF). */
ActorDefinitionPtr makeWalker()
{
    ActorDefinitionBuilder b("walker");
    b.addJoint("pelvis").offset(0, 0, 1).dofs(kRotationDofs | kTranslationDofs);
    b.addJoint("hip", "pelvis").offset(0.1, 0, -0.05).dofs(kRotationDofs)
        .limits(Dof::RX, -2.0, 0.8).limits(Dof::RY, -0.8, 0.8).limits(Dof::RZ, -0.8, 0.8);
    b.addJoint("knee", "hip").offset(0, 0, -0.42).dofs(dofBit(Dof::RX)).limits(Dof::RX, 0.0, 2.6);
    b.addJoint("ankle", "knee").offset(0, 0, -0.41).dofs(dofBit(Dof::RX)).limits(Dof::RX, -0.8, 0.5);
    b.addJoint("toe", "ankle").offset(0, -0.12, -0.04);
    const BuildResult result = b.build();
    EXPECT_TRUE(result) << result.error;
    return result.definition;
}

/** Every DOF within the range a pose holds: its limits, and +-kMaxDofMagnitude (so finite). */
::testing::AssertionResult withinRange(const ActorDefinition& definition, const std::vector<double>& dofs)
{
    for (unsigned d = 0; d < dofs.size(); ++d)
        if (!(dofs[d] >= definition.getDofRangeMin(d) && dofs[d] <= definition.getDofRangeMax(d)))
            return ::testing::AssertionFailure() << definition.getDofName(d) << " = " << dofs[d] << " is outside ["
                                                 << definition.getDofRangeMin(d) << ", " << definition.getDofRangeMax(d)
                                                 << "]";
    return ::testing::AssertionSuccess();
}

/** The walker at rest with the pelvis moved to at by its unlimited translations. */
std::vector<double> pelvisAt(const ActorDefinition& walker, const glm::dvec3& at)
{
    std::vector<double> pose(walker.getNumDofs(), 0.0);
    pose[static_cast<unsigned>(walker.findDof("pelvis.tx"))] = at.x;
    pose[static_cast<unsigned>(walker.findDof("pelvis.ty"))] = at.y;
    pose[static_cast<unsigned>(walker.findDof("pelvis.tz"))] = at.z;
    return pose;
}

/** Start poses: at rest, and with the pelvis carried to the edge of what a pose holds. */
std::vector<std::vector<double>> startPoses(const ActorDefinition& walker)
{
    std::vector<std::vector<double>> poses;
    for (const glm::dvec3& at : {glm::dvec3(0.0), glm::dvec3(kMaxDofMagnitude, 0, 0),
                                 glm::dvec3(kMaxDofMagnitude, -kMaxDofMagnitude, kMaxDofMagnitude),
                                 glm::dvec3(-1e100, 1e100, 0)})
        poses.push_back(pelvisAt(walker, at));
    return poses;
}

/** Goals: far beyond any reach, at the end of the range, mixed signs, with and without a pole and orientation (one
  * of them not normalised, with a norm of 1e150). */
std::vector<IkGoal> extremeGoals()
{
    std::vector<IkGoal> goals;
    for (const glm::dvec3& position : {glm::dvec3(1e300, -1e300, 1e300), glm::dvec3(kMax, 0, 0),
                                       glm::dvec3(-kMax, kMax, -kMax), glm::dvec3(1e154, 1e154, -1e154),
                                       glm::dvec3(0.3, -0.2, 0.4)})
        for (int variant = 0; variant < 4; ++variant)
        {
            IkGoal goal;
            goal.position = position;
            goal.hasPole = variant == 1 || variant == 3;
            goal.pole = glm::dvec3(-kMax, 1e300, 0);
            goal.hasOrientation = variant >= 2;
            goal.orientation = variant == 2 ? glm::dquat(1e150, 1e150, 0, 0) : glm::dquat(0.9, 0.1, -0.3, 0.2);
            goals.push_back(goal);
        }
    return goals;
}

} // namespace

TEST(IkExtremes, HugeFiniteGoalsAndPosesNeverLeaveTheRangeNorGiveNaNErrors)
{
    const ActorDefinitionPtr walker = makeWalker();
    struct Case { const char* root; const char* effector; IkSolverType solver; };
    const Case cases[] = {{"pelvis", "ankle", IkSolverType::Ccd}, {"pelvis", "ankle", IkSolverType::Dls},
                          {"hip", "ankle", IkSolverType::TwoBone}, {"hip", "ankle", IkSolverType::Ccd},
                          {"hip", "ankle", IkSolverType::Dls}, {"hip", "toe", IkSolverType::Dls}};
    for (const Case& c : cases)
        for (unsigned iterations : {1u, 12u, 64u})
        {
            IkChainSpec spec = chainSpec(std::string(c.root) + "-" + c.effector, c.root, c.effector, c.solver);
            spec.maxIterations = iterations;
            const IkChainPtr chain = makeChain(*walker, spec);
            ASSERT_TRUE(chain);
            IkWorkspace workspace;
            workspace.resize(*chain);
            const std::vector<IkGoal> goals = extremeGoals();
            const std::vector<std::vector<double>> starts = startPoses(*walker);
            for (unsigned g = 0; g < goals.size(); ++g)
                for (unsigned s = 0; s < starts.size(); ++s)
                {
                    std::vector<double> dofs = starts[s];
                    IkJob job = makeIkJob(*walker, *chain, goals[g], dofs, workspace);
                    job.rootParentModel = rootParentModel(walker, *chain, dofs);
                    const bool solved = solveIk(job);
                    const std::string where = spec.name + " " + ikSolverName(c.solver) + " iterations " +
                                              std::to_string(iterations) + " goal " + std::to_string(g) + " start " +
                                              std::to_string(s);
                    ASSERT_TRUE(withinRange(*walker, dofs)) << where;
                    EXPECT_FALSE(std::isnan(job.result.positionError)) << where;
                    EXPECT_FALSE(std::isnan(job.result.orientationError)) << where;
                    if (!solved)
                    {
                        EXPECT_EQ(dofs, starts[s]) << where << ": a solve that gives up touches nothing";
                    }
                }
        }
}

TEST(IkExtremes, AStartPoseBeyondWhatAPoseHoldsIsRefused)
{
    const ActorDefinitionPtr walker = makeWalker();
    for (IkSolverType solver : {IkSolverType::Ccd, IkSolverType::Dls})
    {
        const IkChainPtr chain = makeChain(*walker, chainSpec("body", "pelvis", "ankle", solver));
        ASSERT_TRUE(chain);
        for (const glm::dvec3& at : {glm::dvec3(1.01 * kMaxDofMagnitude, 0, 0), glm::dvec3(kMax, -kMax, kMax)})
        {
            const std::vector<double> start = pelvisAt(*walker, at);
            std::vector<double> dofs = start;
            IkWorkspace workspace;
            workspace.resize(*chain);
            IkGoal goal;
            goal.position = glm::dvec3(0.0, 0.0, 1.0);
            IkJob job = makeIkJob(*walker, *chain, goal, dofs, workspace);
            EXPECT_FALSE(solveIk(job)) << ikSolverName(solver) << " from " << at.x;
            EXPECT_EQ(dofs, start);
        }
    }
}
