// The arithmetic the solvers share, checked against independent computations: Euler decomposition against
// composition, the chain's Jacobian against finite differences of the actor's own forward kinematics.
#include "IkTestUtil"
#include "TestMath"

#include <osgActor/core/ik/IkKinematics>

#include <glm/ext/matrix_transform.hpp>
#include <glm/geometric.hpp>

using namespace osgActor;
using namespace osgActor::test;

namespace {

glm::dmat3 elementary(unsigned axis, double angle)
{
    glm::dvec3 a(0.0);
    a[axis] = 1.0;
    return glm::dmat3(glm::rotate(glm::dmat4(1.0), angle, a));
}

/** An actor that uses every kinematic option: Euler orders, an offset rotation, translation DOFs after and before
  * rotation. */
ActorDefinitionPtr makeMixedActor()
{
    ActorDefinitionBuilder b("mixed");
    b.addJoint("root").offset(0.3, 0.2, 0.1).rotation(0.4, 1, 1, 0).dofs(kRotationDofs).eulerOrder(EulerOrder::ZXY);
    b.addJoint("slider", "root").offset(0.5, 0, 0).dofs(Dof::RY | Dof::TX).limits(Dof::TX, -0.2, 0.4);
    b.addJoint("mocap", "slider").offset(0, 0.4, 0.1).rotation(-0.7, 0, 0, 1)
        .dofs(kRotationDofs | Dof::TY | Dof::TZ).eulerOrder(EulerOrder::YZX)
        .translationMode(TranslationMode::BeforeRotation);
    b.addJoint("end", "mocap").offset(0.2, 0.1, -0.3);
    const BuildResult result = b.build();
    EXPECT_TRUE(result) << result.error;
    return result.definition;
}

} // namespace

TEST(IkKinematics, EulerDecompositionRecomposesForEveryOrder)
{
    std::mt19937 random(1);
    std::uniform_real_distribution<double> angle(-3.0, 3.0);
    for (unsigned o = 0; o < 6; ++o)
    {
        const EulerOrder order = static_cast<EulerOrder>(o);
        unsigned axes3[3];
        eulerOrderAxes(order, axes3);
        const std::uint8_t axes[3] = {std::uint8_t(axes3[0]), std::uint8_t(axes3[1]), std::uint8_t(axes3[2])};
        for (int i = 0; i < 200; ++i)
        {
            double in[3] = {angle(random), angle(random), angle(random)};
            if (i < 4) in[1] = (i % 2 ? -0.5 : 0.5) * glm::pi<double>(); // gimbal lock
            const glm::dmat3 m = elementary(axes[0], in[0]) * elementary(axes[1], in[1]) * elementary(axes[2], in[2]);
            double first[3], second[3];
            decomposeEuler(m, axes, first, second);
            EXPECT_LE(std::abs(first[1]), 0.5 * glm::pi<double>() + 1e-12);
            for (const double* out : {first, second})
            {
                const glm::dmat3 back = elementary(axes[0], out[0]) * elementary(axes[1], out[1]) *
                                        elementary(axes[2], out[2]);
                EXPECT_TRUE(matricesNear(glm::dmat4(back), glm::dmat4(m), 1e-9))
                    << eulerOrderName(order) << " " << in[0] << " " << in[1] << " " << in[2];
            }
        }
    }
}

TEST(IkKinematics, FitAngleToLimits)
{
    const double pi = glm::pi<double>();
    EXPECT_DOUBLE_EQ(fitAngleToLimits(0.5, -1.0, 1.0, 0.0), 0.5);
    EXPECT_NEAR(fitAngleToLimits(0.5 + 2 * pi, -1.0, 1.0, 0.0), 0.5, 1e-12) << "a turn away";
    EXPECT_NEAR(fitAngleToLimits(-3.0, 0.0, 4.0, 0.0), 2 * pi - 3.0, 1e-12) << "the turn that fits";
    EXPECT_NEAR(fitAngleToLimits(1.0, -10.0, 10.0, 6.0), 1.0 + 2 * pi, 1e-12) << "nearest the reference";
    EXPECT_EQ(fitAngleToLimits(1.5, -1.0, 1.0, 0.0), 1.0) << "nearest limit";
    EXPECT_EQ(fitAngleToLimits(-2.0, -1.0, 1.0, 0.0), -1.0);
    EXPECT_EQ(fitAngleToLimits(3.0, -1.0, 1.0, 0.0), 1.0) << "2 rad from 1, 2 pi - 4 from -1";
    EXPECT_EQ(fitAngleToLimits(3.5, -1.0, 1.0, 0.0), -1.0) << "closer to -1 going round the circle";
}

TEST(IkKinematics, RotationVectorMatchesAxisAndAngle)
{
    const glm::dvec3 axis = glm::normalize(glm::dvec3(0.3, -0.5, 0.8));
    for (double angle : {0.0, 1e-9, 0.3, 2.0, 3.1, glm::pi<double>() - 1e-7})
    {
        const glm::dmat3 r(glm::rotate(glm::dmat4(1.0), angle, axis));
        EXPECT_TRUE(vectorsNear(rotationVector(r), axis * angle, 1e-6)) << angle;
    }
    const glm::dmat3 halfTurn(glm::rotate(glm::dmat4(1.0), glm::pi<double>(), axis));
    const glm::dvec3 v = rotationVector(halfTurn);
    EXPECT_NEAR(glm::length(v), glm::pi<double>(), 1e-9);
    EXPECT_NEAR(std::abs(glm::dot(glm::normalize(v), axis)), 1.0, 1e-9);
}

TEST(IkKinematics, ChainPoseMatchesTheActorsForwardKinematics)
{
    const ActorDefinitionPtr mixed = makeMixedActor();
    const IkChainPtr chain =
        makeChain(*mixed, chainSpec("c", "slider", "end", IkSolverType::Dls, glm::dvec3(0.1, 0.2, 0.3)));
    std::mt19937 random(2);
    IkWorkspace workspace;
    workspace.resize(*chain);
    for (int i = 0; i < 20; ++i)
    {
        const std::vector<double> dofs = randomPose(*mixed, random);
        const std::vector<glm::dmat4> models = modelMatrices(mixed, dofs);
        computeChainPose(*mixed, *chain, models[0], dofs.data(), workspace);
        for (unsigned c = 0; c < chain->getNumJoints(); ++c)
            EXPECT_TRUE(matricesNear(workspace.jointModel[c], models[chain->getJoint(c)], 1e-12));
        EXPECT_TRUE(vectorsNear(workspace.effectorPosition, effectorPoint(mixed, *chain, dofs), 1e-12));
    }
}

TEST(IkKinematics, JacobianMatchesFiniteDifferences)
{
    const ActorDefinitionPtr mixed = makeMixedActor();
    const IkChainPtr chain =
        makeChain(*mixed, chainSpec("c", "root", "end", IkSolverType::Dls, glm::dvec3(0.1, 0.2, 0.3)));
    ASSERT_EQ(chain->getNumDofs(), mixed->getNumDofs()) << "every DOF of the actor is in the chain";
    std::mt19937 random(3);
    IkWorkspace workspace;
    workspace.resize(*chain);
    const double h = 1e-6;
    for (int i = 0; i < 20; ++i)
    {
        std::vector<double> dofs = randomPose(*mixed, random);
        for (double& v : dofs) v = std::max(std::min(v, 0.39), -0.19); // room for the slide's difference
        computeChainPose(*mixed, *chain, glm::dmat4(1.0), dofs.data(), workspace);
        computeDofAxes(*mixed, *chain, dofs.data(), workspace);
        const glm::dvec3 effector = workspace.effectorPosition;
        for (unsigned d = 0; d < chain->getNumDofs(); ++d)
        {
            const IkChainDof& chainDof = chain->getDof(d);
            std::vector<double> plus = dofs, minus = dofs;
            plus[chainDof.dof] += h;
            minus[chainDof.dof] -= h;
            const glm::dvec3 numeric =
                (effectorPoint(mixed, *chain, plus) - effectorPoint(mixed, *chain, minus)) / (2.0 * h);
            const glm::dvec3 analytic = isRotation(chainDof.type)
                                            ? glm::cross(workspace.axis[d], effector - workspace.pivot[d])
                                            : workspace.axis[d];
            EXPECT_TRUE(vectorsNear(analytic, numeric, 1e-7)) << mixed->getDofName(chainDof.dof);
            if (isRotation(chainDof.type))
            {
                // The frame turns about the axis: (R(+h) R(-h)^T) is a rotation of 2h about it.
                const glm::dquat turn = effectorOrientation(mixed, *chain, plus) *
                                        glm::inverse(effectorOrientation(mixed, *chain, minus));
                const glm::dvec3 numericAxis = rotationVector(glm::mat3_cast(turn)) / (2.0 * h);
                EXPECT_TRUE(vectorsNear(workspace.axis[d], numericAxis, 1e-6)) << mixed->getDofName(chainDof.dof);
            }
        }
    }
}
