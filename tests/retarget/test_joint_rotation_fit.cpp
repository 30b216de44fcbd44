// The joint rotation fit (fitJointRotationDofs) of joints with two rotations: the angles whose rotation is nearest
// the asked one in least squares, checked against an independent search (a grid over both angles, then coordinate
// descent run to convergence from its best point), for every order of two axes.
#include "RetargetTestUtil"

#include <osgActor/core/retarget/JointRotationFit>

#include <glm/gtc/quaternion.hpp>

#include <cmath>
#include <random>

using namespace osgActor;
using namespace osgActor::test;

namespace {

glm::dmat3 axisRotation(unsigned axis, double angle)
{
    glm::dvec3 a(0.0);
    a[static_cast<int>(axis)] = 1.0;
    return glm::mat3_cast(glm::angleAxis(angle, a));
}

double squaredDistance(const glm::dmat3& a, const glm::dmat3& b)
{
    double sum = 0.0;
    for (int c = 0; c < 3; ++c)
        for (int r = 0; r < 3; ++r) sum += (a[c][r] - b[c][r]) * (a[c][r] - b[c][r]);
    return sum;
}

/** The least squared distance from R_a0(x) R_a1(y) to target, by brute force: a 1-degree grid, then rounds of a
  * fine 1D search on each angle in turn until nothing moves. */
double nearestBySearch(const glm::dmat3& target, unsigned a0, unsigned a1)
{
    const double step = degrees(1.0);
    double best = 1e300, x = 0.0, y = 0.0;
    for (double i = -180.0; i < 180.0; i += 1.0)
        for (double j = -180.0; j < 180.0; j += 1.0)
        {
            const double d = squaredDistance(axisRotation(a0, degrees(i)) * axisRotation(a1, degrees(j)), target);
            if (d < best) best = d, x = degrees(i), y = degrees(j);
        }
    for (unsigned round = 0; round < 200; ++round)
    {
        const double before = best;
        for (double h = step; h > 1e-12; h *= 0.5)
            for (int side : {-1, 1})
            {
                const double dx = squaredDistance(axisRotation(a0, x + side * h) * axisRotation(a1, y), target);
                if (dx < best) best = dx, x += side * h;
                const double dy = squaredDistance(axisRotation(a0, x) * axisRotation(a1, y + side * h), target);
                if (dy < best) best = dy, y += side * h;
            }
        if (before - best < 1e-16) break;
    }
    return best;
}

} // namespace

TEST(JointRotationFit, TwoRotationsComeAsNearAsAnyPairOfAnglesCan)
{
    std::mt19937 random(27);
    std::uniform_real_distribution<double> angle(-3.1, 3.1), coordinate(-1.0, 1.0);
    const std::pair<DofMask, EulerOrder> joints[] = {
        {dofBit(Dof::RX) | dofBit(Dof::RY), EulerOrder::XYZ}, {dofBit(Dof::RX) | dofBit(Dof::RY), EulerOrder::YXZ},
        {dofBit(Dof::RY) | dofBit(Dof::RZ), EulerOrder::XYZ}, {dofBit(Dof::RY) | dofBit(Dof::RZ), EulerOrder::XZY},
        {dofBit(Dof::RX) | dofBit(Dof::RZ), EulerOrder::XYZ}, {dofBit(Dof::RX) | dofBit(Dof::RZ), EulerOrder::ZYX}};
    for (const auto& [mask, order] : joints)
    {
        ActorDefinitionBuilder b("two");
        b.addJoint("j").dofs(mask).eulerOrder(order);
        const ActorDefinitionPtr definition = b.build().definition;
        ASSERT_TRUE(definition);
        const JointKinematics& k = definition->getKinematics(0);
        ASSERT_EQ(k.numRotations, 2u);
        const unsigned a0 = k.rotationAxis[0], a1 = k.rotationAxis[1];
        for (unsigned trial = 0; trial < 4; ++trial)
        {
            // A rotation two angles make exactly: found again, to rounding.
            const double x = angle(random), y = angle(random);
            const glm::dmat3 reachable = axisRotation(a0, x) * axisRotation(a1, y);
            std::vector<double> dofs(definition->getNumDofs(), 0.0);
            EXPECT_FALSE(fitJointRotationDofs(*definition, 0, reachable, dofs.data())); // two rotations: never exact
            EXPECT_LE(squaredDistance(jointRotation(k, dofs.data()), reachable), 1e-24) << a0 << a1;

            // Any rotation: as near as the search's best, or nearer.
            const glm::dvec3 axis(coordinate(random), coordinate(random), coordinate(random));
            const glm::dmat3 any = glm::mat3_cast(glm::angleAxis(angle(random), glm::normalize(axis)));
            std::fill(dofs.begin(), dofs.end(), 0.0);
            fitJointRotationDofs(*definition, 0, any, dofs.data());
            EXPECT_LE(squaredDistance(jointRotation(k, dofs.data()), any), nearestBySearch(any, a0, a1) + 1e-12)
                << "axes " << a0 << " " << a1 << ", trial " << trial;
        }
    }
}
