#include <osgActor/io/AngleAxis>
#include <osgActor/text/Degrees>
#include <osgActor/text/Numbers>

#include <glm/ext/quaternion_trigonometric.hpp>
#include <glm/ext/vector_double3.hpp>

#include <cmath>
#include <limits>

namespace osgActor {

namespace {

/** How many steps of one unit in the last place toExactAngleAxis() tries on each side of the angle and of each
  * axis component that is not 0 or +-1: the reader's normalization and trigonometry round a few times. */
constexpr int kSearchSteps = 2;

/** A quaternion's length, squared, counts as 1 within this (a unit quaternion computed in doubles is within a few
  * units in the last place; one typed by hand to 4 decimals is 1e-4 off). */
constexpr double kUnitLengthTolerance = 1e-12;

bool sameRotation(const glm::dquat& a, const glm::dquat& b)
{
    return (a.w == b.w && a.x == b.x && a.y == b.y && a.z == b.z) ||
           (a.w == -b.w && a.x == -b.x && a.y == -b.y && a.z == -b.z);
}

/** The candidates for one written number: value, then the doubles one, two, ... steps away on either side; a
  * component that is exactly 0 or +-1 (the axis' largest) is exact already and has no other candidate. */
int candidates(double value, bool exact, double* out)
{
    out[0] = value;
    if (exact) return 1;
    int count = 1;
    double below = value, above = value;
    for (int step = 0; step < kSearchSteps; ++step)
    {
        below = std::nextafter(below, -std::numeric_limits<double>::infinity());
        above = std::nextafter(above, std::numeric_limits<double>::infinity());
        out[count++] = below;
        out[count++] = above;
    }
    return count;
}

} // namespace

bool toQuaternion(const AngleAxis& angleAxis, glm::dquat& rotation)
{
    const glm::dvec3 axis(angleAxis.axis[0], angleAxis.axis[1], angleAxis.axis[2]);
    const double length = std::sqrt(axis.x * axis.x + axis.y * axis.y + axis.z * axis.z);
    if (!(length > 0.0) || !std::isfinite(length)) return false;
    rotation = glm::angleAxis(radiansFromDegrees(angleAxis.degrees), axis / length);
    return true;
}

AngleAxis toAngleAxis(const glm::dquat& rotation)
{
    // The same rotation with w >= 0 has its angle in [0, 180] degrees.
    const glm::dquat q = rotation.w < 0.0 ? -rotation : rotation;
    const double sine = std::hypot(q.x, q.y, q.z); // sin(angle / 2), without underflow for tiny angles
    AngleAxis result;
    if (sine == 0.0) return result; // the identity; the axis does not matter
    result.degrees = 2.0 * std::atan2(sine, q.w) * kDegreesPerRadian;
    const double components[3] = {q.x, q.y, q.z};
    double largest = 0.0;
    for (const double c : components) largest = std::abs(c) > std::abs(largest) ? c : largest;
    // Scaling by the largest component instead of normalizing keeps the ratios of the components as they are.
    for (unsigned i = 0; i < 3; ++i) result.axis[i] = components[i] / std::abs(largest);
    return result;
}

bool toExactAngleAxis(const glm::dquat& rotation, AngleAxis& angleAxis)
{
    const AngleAxis near = toAngleAxis(rotation);
    constexpr int kMax = 1 + 2 * kSearchSteps;
    double angles[kMax], axes[3][kMax];
    const int numAngles = candidates(near.degrees, false, angles);
    int numAxes[3];
    for (unsigned i = 0; i < 3; ++i)
        numAxes[i] = candidates(near.axis[i], near.axis[i] == 0.0 || std::abs(near.axis[i]) == 1.0, axes[i]);
    for (int a = 0; a < numAngles; ++a)
        for (int x = 0; x < numAxes[0]; ++x)
            for (int y = 0; y < numAxes[1]; ++y)
                for (int z = 0; z < numAxes[2]; ++z)
                {
                    AngleAxis candidate;
                    candidate.degrees = angles[a];
                    candidate.axis[0] = axes[0][x];
                    candidate.axis[1] = axes[1][y];
                    candidate.axis[2] = axes[2][z];
                    glm::dquat q;
                    if (toQuaternion(candidate, q) && sameRotation(q, rotation))
                    {
                        angleAxis = candidate;
                        return true;
                    }
                }
    return false;
}

glm::dquat nearestWrittenRotation(const glm::dquat& rotation)
{
    constexpr int kDigits = 12;
    constexpr double kTolerance = 8.0 * std::numeric_limits<double>::epsilon(); // components are at most 1
    AngleAxis rounded = toAngleAxis(rotation);
    rounded.degrees = roundToSignificantDigits(rounded.degrees, kDigits);
    for (double& component : rounded.axis) component = roundToSignificantDigits(component, kDigits);
    glm::dquat q;
    if (!toQuaternion(rounded, q)) return rotation;
    if (q.w * rotation.w + q.x * rotation.x + q.y * rotation.y + q.z * rotation.z < 0.0) q = -q;
    const bool near = std::abs(q.w - rotation.w) <= kTolerance && std::abs(q.x - rotation.x) <= kTolerance &&
                      std::abs(q.y - rotation.y) <= kTolerance && std::abs(q.z - rotation.z) <= kTolerance;
    return near ? q : rotation;
}

bool quaternionAsWritten(const double wxyz[4], glm::dquat& rotation)
{
    const glm::dquat q(wxyz[0], wxyz[1], wxyz[2], wxyz[3]);
    const double lengthSquared = q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z;
    if (!(lengthSquared > 0.0) || !std::isfinite(lengthSquared)) return false;
    if (std::abs(lengthSquared - 1.0) <= kUnitLengthTolerance)
    {
        rotation = q;
        return true;
    }
    const double length = std::sqrt(lengthSquared);
    rotation = glm::dquat(q.w / length, q.x / length, q.y / length, q.z / length);
    return true;
}

bool isIdentityRotation(const glm::dquat& rotation) { return sameRotation(rotation, glm::dquat(1.0, 0.0, 0.0, 0.0)); }

} // namespace osgActor
