// CCD's sweep acceleration (SweepAcceleration) on maps whose fixed point is known: Anderson mixing of a linear
// contraction finds its fixed point, a pattern move follows the last sweep, and neither proposes without grounds.
#include "IkTestUtil"

#include <osgActor/core/ik/SweepAcceleration>

#include <glm/mat3x3.hpp>

using namespace osgActor;
using namespace osgActor::test;

namespace {

/** A three-DOF chain of the snake (s0 .. s2): only its DOF count, DOF types and length matter here. */
IkChainPtr threeDofChain(const ActorDefinitionPtr& snake)
{
    return makeChain(*snake, chainSpec("three", "s0", "s2", IkSolverType::Ccd, glm::dvec3(0.2, 0, 0)));
}

/** A slow linear "sweep": q -> A q + b, contracting slowly (eigenvalues 0.97, 0.9, 0.5) and not symmetric. */
glm::dvec3 slowSweep(const glm::dvec3& q)
{
    const glm::dmat3 a(0.97, 0.02, 0.0, /**/ 0.0, 0.9, 0.01, /**/ 0.0, 0.0, 0.5); // columns
    return a * q + glm::dvec3(0.03, -0.05, 0.2);
}

} // namespace

TEST(SweepAcceleration, ProposesNothingWithoutTwoSweepsOrWithoutProgress)
{
    const ActorDefinitionPtr snake = makeSnakeActor();
    const IkChainPtr chain = threeDofChain(snake);
    ASSERT_EQ(chain->getNumDofs(), 3u);
    IkWorkspace workspace;
    workspace.resize(*chain);
    SweepHistory history;
    double proposed[3] = {7, 7, 7};
    EXPECT_FALSE(proposeAndersonMix(*chain, workspace, history, proposed)) << "no sweep yet";
    const double start[3] = {0.1, 0.2, 0.3}, end[3] = {0.2, 0.1, 0.3};
    history.record(*chain, start, end, workspace);
    EXPECT_FALSE(proposeAndersonMix(*chain, workspace, history, proposed)) << "one sweep";
    // Sweeps that moved nothing (a chain at a fixed point, or held by its limits): nothing to mix.
    SweepHistory still;
    for (int i = 0; i < 3; ++i) still.record(*chain, start, start, workspace);
    EXPECT_FALSE(proposeAndersonMix(*chain, workspace, still, proposed));
    for (double value : proposed) EXPECT_EQ(value, 7.0) << "nothing written";
}

TEST(SweepAcceleration, AndersonMixingFindsTheFixedPointOfALinearSweep)
{
    const ActorDefinitionPtr snake = makeSnakeActor();
    const IkChainPtr chain = threeDofChain(snake);
    IkWorkspace workspace;
    workspace.resize(*chain);
    // The fixed point q* = (I - A)^-1 b.
    const glm::dmat3 a(0.97, 0.02, 0.0, 0.0, 0.9, 0.01, 0.0, 0.0, 0.5);
    const glm::dvec3 fixedPoint = glm::inverse(glm::dmat3(1.0) - a) * glm::dvec3(0.03, -0.05, 0.2);

    // Four plain sweeps from q0 get nowhere near it (the slowest mode shrinks by 0.97 a sweep)...
    SweepHistory history;
    glm::dvec3 q(0.0);
    for (unsigned i = 0; i < kSweepHistory; ++i)
    {
        const glm::dvec3 next = slowSweep(q);
        history.record(*chain, &q.x, &next.x, workspace);
        q = next;
    }
    EXPECT_GT(glm::length(q - fixedPoint), 0.1);
    // ... but mixing their three differences solves the three-dimensional linear problem (a secant step).
    glm::dvec3 proposed(0.0);
    ASSERT_TRUE(proposeAndersonMix(*chain, workspace, history, &proposed.x));
    EXPECT_LT(glm::length(proposed - fixedPoint), 1e-8);

    // The history keeps the latest kSweepHistory sweeps: one more sweep still mixes to the fixed point.
    const glm::dvec3 next = slowSweep(q);
    history.record(*chain, &q.x, &next.x, workspace);
    EXPECT_EQ(history.count, kSweepHistory);
    ASSERT_TRUE(proposeAndersonMix(*chain, workspace, history, &proposed.x));
    EXPECT_LT(glm::length(proposed - fixedPoint), 1e-8);
}

TEST(SweepAcceleration, APatternMoveFollowsTheLastSweep)
{
    const ActorDefinitionPtr snake = makeSnakeActor();
    const IkChainPtr chain = threeDofChain(snake);
    const double start[3] = {0.1, 0.2, 0.3}, end[3] = {0.2, 0.1, 0.3};
    double proposed[3];
    proposePatternMove(*chain, start, end, 4.0, proposed);
    EXPECT_DOUBLE_EQ(proposed[0], 0.6);
    EXPECT_DOUBLE_EQ(proposed[1], -0.3);
    EXPECT_DOUBLE_EQ(proposed[2], 0.3);
}
