#include <osgActor/import/EulerFit>

#include <osgActor/core/ik/IkKinematics>

#include <glm/ext/quaternion_trigonometric.hpp>
#include <glm/gtc/quaternion.hpp>

#include <cmath>
#include <limits>

namespace osgActor {

namespace {

const EulerOrder kOrders[6] = {EulerOrder::XYZ, EulerOrder::XZY, EulerOrder::YXZ,
                               EulerOrder::YZX, EulerOrder::ZXY, EulerOrder::ZYX};

void orderAxes(EulerOrder order, std::uint8_t axes[3])
{
    unsigned a[3];
    eulerOrderAxes(order, a);
    for (unsigned i = 0; i < 3; ++i) axes[i] = static_cast<std::uint8_t>(a[i]);
}

/** angle turned by whole turns to lie within half a turn of reference. */
double nearestTurn(double angle, double reference)
{
    const double twoPi = 2.0 * glm::pi<double>();
    return angle + twoPi * std::round((reference - angle) / twoPi);
}

} // namespace

glm::dquat eulerRotation(EulerOrder order, const double angles[3])
{
    std::uint8_t axes[3];
    orderAxes(order, axes);
    glm::dquat q(1.0, 0.0, 0.0, 0.0);
    for (unsigned i = 0; i < 3; ++i)
    {
        glm::dvec3 axis(0.0);
        axis[axes[i]] = 1.0;
        q = q * glm::angleAxis(angles[i], axis);
    }
    return q;
}

void eulerAngles(const glm::dquat& rotation, EulerOrder order, const double* previous, double angles[3])
{
    std::uint8_t axes[3];
    orderAxes(order, axes);
    double solutions[2][3];
    decomposeEuler(glm::mat3_cast(rotation), axes, solutions[0], solutions[1]);
    if (!previous)
    {
        for (unsigned i = 0; i < 3; ++i) angles[i] = solutions[0][i];
        return;
    }
    double best = std::numeric_limits<double>::infinity();
    for (auto& solution : solutions)
    {
        double distance = 0.0;
        for (unsigned i = 0; i < 3; ++i)
        {
            solution[i] = nearestTurn(solution[i], previous[i]);
            distance += std::abs(solution[i] - previous[i]);
        }
        if (distance < best)
        {
            best = distance;
            for (unsigned i = 0; i < 3; ++i) angles[i] = solution[i];
        }
    }
}

double gimbalMargin(const glm::dquat& rotation, EulerOrder order)
{
    std::uint8_t axes[3];
    orderAxes(order, axes);
    double first[3], second[3];
    decomposeEuler(glm::mat3_cast(rotation), axes, first, second);
    return std::abs(std::cos(first[1]));
}

EulerOrder chooseEulerOrder(const std::vector<glm::dquat>& rotations, double* margin)
{
    EulerOrder best = EulerOrder::XYZ;
    double bestMargin = -1.0;
    for (EulerOrder order : kOrders)
    {
        double worst = 1.0;
        for (const glm::dquat& q : rotations) worst = std::min(worst, gimbalMargin(q, order));
        if (worst > bestMargin + 1e-9)
        {
            bestMargin = worst;
            best = order;
        }
    }
    if (margin) *margin = bestMargin;
    return best;
}

} // namespace osgActor
