// One CCD sweep turns a joint's DOFs one after another. Turning one moves the axes of the DOFs after it in the
// joint's rotation product (and, for a joint that slides before it rotates, a slide moves its rotations' pivot):
// the sweep must keep them current, or it turns about one axis while the pose turns about another. The check: the
// effector the sweep tracked equals the one forward kinematics gives for the DOFs it wrote.
#include "IkTestUtil"

#include <osgActor/core/ik/CcdIkJob>
#include <osgActor/core/ik/IkKinematics>

#include <glm/geometric.hpp>

using namespace osgActor;
using namespace osgActor::test;

namespace {

/** A ball joint (three rotations in the given Euler order, optionally three slides) with a one-unit bone to a tip. */
ActorDefinitionPtr ballJoint(EulerOrder order, bool slides, TranslationMode mode)
{
    ActorDefinitionBuilder b("ball");
    DofMask dofs = kRotationDofs;
    if (slides) dofs = static_cast<DofMask>(dofs | dofBit(Dof::TX) | dofBit(Dof::TY) | dofBit(Dof::TZ));
    b.addJoint("ball").offset(0.0, 0.5, 0.0).dofs(dofs).eulerOrder(order).translationMode(mode);
    b.addJoint("tip", "ball").offset(0.2, 1.0, -0.3);
    const BuildResult result = b.build();
    EXPECT_TRUE(result) << result.error;
    return result.definition;
}

/** After one sweep from a skewed start toward a goal, the distance between the effector the sweep tracked and the
  * one FK gives for the DOFs it wrote. */
double trackingError(const ActorDefinitionPtr& def, bool orientation)
{
    const IkChainPtr chain = makeChain(*def, chainSpec("arm", "ball", "tip", IkSolverType::Ccd));
    std::vector<double> dofs(def->getNumDofs(), 0.0);
    for (unsigned d = 0; d < dofs.size(); ++d) dofs[d] = 0.3 + 0.25 * d; // every axis skewed
    IkGoal goal;
    goal.position = glm::dvec3(-0.6, 0.4, 0.9);
    goal.hasOrientation = orientation;
    goal.orientation = glm::angleAxis(0.7, glm::normalize(glm::dvec3(1.0, 2.0, -1.0)));
    IkWorkspace workspace;
    workspace.resize(*chain);
    const IkJob job = makeIkJob(*def, *chain, goal, dofs, workspace);
    startChainPose(job);
    computeDofAxes(*def, *chain, dofs.data(), workspace);
    const glm::dmat3 goalRotation = glm::mat3_cast(goal.orientation);
    runCcdSweep(*chain, goal, goalRotation, 1.0, orientation ? 1.0 : 0.0, true, 0, chain->getNumDofs(), dofs.data(),
                workspace);
    const glm::dvec3 tracked = workspace.effectorPosition;
    return glm::length(tracked - effectorPoint(def, *chain, dofs));
}

} // namespace

TEST(CcdSweep, TracksTheEffectorForEveryEulerOrder)
{
    for (unsigned o = 0; o < 6; ++o)
    {
        const EulerOrder order = static_cast<EulerOrder>(o);
        EXPECT_LT(trackingError(ballJoint(order, false, TranslationMode::AfterRotation), false), 1e-12)
            << eulerOrderName(order);
        EXPECT_LT(trackingError(ballJoint(order, false, TranslationMode::AfterRotation), true), 1e-12)
            << eulerOrderName(order) << ", with an orientation goal";
    }
}

TEST(CcdSweep, TracksTheEffectorWithSlidesInEitherTranslationMode)
{
    for (const TranslationMode mode : {TranslationMode::AfterRotation, TranslationMode::BeforeRotation})
        for (unsigned o = 0; o < 6; ++o)
        {
            const EulerOrder order = static_cast<EulerOrder>(o);
            // With an orientation goal, so the rotations still turn once the slides have reached the position.
            EXPECT_LT(trackingError(ballJoint(order, true, mode), true), 1e-12)
                << eulerOrderName(order) << (mode == TranslationMode::AfterRotation ? ", after" : ", before");
        }
}
