#include <osgActor/io/ActorNumbers>

#include <glm/ext/quaternion_trigonometric.hpp>
#include <glm/ext/scalar_constants.hpp>
#include <glm/ext/vector_double3.hpp>

#include <charconv>
#include <cmath>
#include <limits>

namespace osgActor {

namespace {

constexpr double kZeroBelow = 1e-12;
constexpr int kSignificantDigits = 12;

} // namespace

namespace {

/** Parses the whole word, finite or not; false when it is no number at all. Out of range counts as infinite. */
bool parseAnyNumber(const std::string& word, double& value)
{
    if (word.empty()) return false;
    const char* first = word.data();
    const char* last = first + word.size();
    if (*first == '+') ++first; // from_chars refuses a leading '+', people write one
    const std::from_chars_result result = std::from_chars(first, last, value);
    if (result.ptr != last) return false;
    if (result.ec == std::errc::result_out_of_range) value = std::numeric_limits<double>::infinity();
    else if (result.ec != std::errc()) return false;
    return true;
}

} // namespace

bool parseNumber(const std::string& word, double& value)
{
    double parsed = 0.0;
    if (!parseAnyNumber(word, parsed) || !std::isfinite(parsed)) return false;
    value = parsed;
    return true;
}

bool isNonFiniteNumber(const std::string& word)
{
    double parsed = 0.0;
    return parseAnyNumber(word, parsed) && !std::isfinite(parsed);
}

std::string formatNumber(double value)
{
    if (!(std::abs(value) >= kZeroBelow)) return "0"; // also NaN, which files cannot hold
    char buffer[64];
    const std::to_chars_result result =
        std::to_chars(buffer, buffer + sizeof(buffer), value, std::chars_format::general, kSignificantDigits);
    return std::string(buffer, result.ptr);
}

bool toQuaternion(const AngleAxis& angleAxis, glm::dquat& rotation)
{
    const glm::dvec3 axis(angleAxis.axis[0], angleAxis.axis[1], angleAxis.axis[2]);
    const double length = std::sqrt(axis.x * axis.x + axis.y * axis.y + axis.z * axis.z);
    if (!(length > 0.0) || !std::isfinite(length)) return false;
    rotation = glm::angleAxis(angleAxis.degrees * (glm::pi<double>() / 180.0), axis / length);
    return true;
}

AngleAxis toAngleAxis(const glm::dquat& rotation)
{
    // The same rotation with w >= 0 has its angle in [0, 180] degrees.
    const glm::dquat q = rotation.w < 0.0 ? -rotation : rotation;
    const double sine = std::sqrt(q.x * q.x + q.y * q.y + q.z * q.z); // sin(angle / 2)
    AngleAxis result;
    if (sine == 0.0) return result; // the identity; the axis does not matter
    result.degrees = 2.0 * std::atan2(sine, q.w) * (180.0 / glm::pi<double>());
    const double components[3] = {q.x, q.y, q.z};
    double largest = 0.0;
    for (const double c : components) largest = std::abs(c) > std::abs(largest) ? c : largest;
    for (unsigned i = 0; i < 3; ++i) result.axis[i] = components[i] / std::abs(largest);
    return result;
}

bool isIdentityRotation(const glm::dquat& rotation)
{
    return formatNumber(toAngleAxis(rotation).degrees) == "0";
}

} // namespace osgActor
