#include <osgActor/io/ActorNumbers>

#include <glm/ext/quaternion_trigonometric.hpp>
#include <glm/ext/scalar_constants.hpp>
#include <glm/ext/vector_double3.hpp>

#include <charconv>
#include <cstdint>
#include <cmath>
#include <limits>

namespace osgActor {

namespace {

constexpr double kZeroBelow = 1e-12;
constexpr int kSignificantDigits = 12;

} // namespace

namespace {

/** Exact powers of ten up to 1e22, the largest a double holds exactly. */
const double kPowersOfTen[] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,  1e8,  1e9,  1e10, 1e11,
                               1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};

/** Clinger's fast path: a decimal whose digits fit in 53 bits, scaled by at most 10^22, is one correctly rounded
  * multiplication or division of two exact doubles, so the result equals strtod's. Mocap numbers ("-0.000000",
  * "27.973049", ".0083333", "1e-014") nearly all take it; false sends the rest to std::from_chars. */
bool parseDecimalFast(std::string_view token, double& value)
{
    const char* p = token.data();
    const char* const end = p + token.size();
    const bool negative = p != end && *p == '-';
    if (negative) ++p;
    std::uint64_t mantissa = 0;
    int digits = 0;   // significant digits kept in mantissa
    int exponent = 0; // power of ten to apply
    bool any = false;
    for (; p != end && *p >= '0' && *p <= '9'; ++p, any = true)
    {
        if (mantissa == 0 && *p == '0') continue; // leading zeros are not significant
        if (++digits > 19) return false;
        mantissa = mantissa * 10 + static_cast<unsigned>(*p - '0');
    }
    if (p != end && *p == '.')
    {
        for (++p; p != end && *p >= '0' && *p <= '9'; ++p, any = true)
        {
            --exponent;
            if (mantissa == 0 && *p == '0') continue;
            if (++digits > 19) return false;
            mantissa = mantissa * 10 + static_cast<unsigned>(*p - '0');
        }
    }
    if (!any) return false;
    if (p != end && (*p == 'e' || *p == 'E'))
    {
        ++p;
        const bool negativeExponent = p != end && *p == '-';
        if (p != end && (*p == '-' || *p == '+')) ++p;
        if (p == end) return false;
        int written = 0;
        for (; p != end && *p >= '0' && *p <= '9'; ++p)
        {
            if (written > 1000) return false;
            written = written * 10 + (*p - '0');
        }
        exponent += negativeExponent ? -written : written;
    }
    if (p != end) return false;
    if (mantissa > (std::uint64_t(1) << 53) || exponent < -22 || exponent > 22)
        return mantissa == 0 ? (value = negative ? -0.0 : 0.0, true) : false;
    const double m = static_cast<double>(mantissa);
    value = exponent < 0 ? m / kPowersOfTen[-exponent] : m * kPowersOfTen[exponent];
    if (negative) value = -value;
    return true;
}

/** For a decimal word from_chars found out of range: whether it is too large (an overflow), not too small (an
  * underflow). The decimal point of its first significant digit, shifted by the exponent, says which. */
bool overflows(std::string_view word)
{
    std::size_t i = word.front() == '-' ? 1 : 0;
    long position = 0; // the power of ten just above the first significant digit
    bool significant = false;
    for (; i < word.size() && word[i] >= '0' && word[i] <= '9'; ++i)
        if (significant || word[i] != '0')
        {
            significant = true;
            ++position;
        }
    if (i < word.size() && word[i] == '.')
        for (++i; i < word.size() && word[i] >= '0' && word[i] <= '9'; ++i)
        {
            if (significant) continue;
            if (word[i] != '0') significant = true;
            else --position;
        }
    long exponent = 0;
    if (i < word.size() && (word[i] == 'e' || word[i] == 'E'))
    {
        ++i;
        const bool negative = i < word.size() && word[i] == '-';
        if (i < word.size() && (word[i] == '-' || word[i] == '+')) ++i;
        for (; i < word.size() && word[i] >= '0' && word[i] <= '9' && exponent < 100000; ++i)
            exponent = exponent * 10 + (word[i] - '0');
        if (negative) exponent = -exponent;
    }
    return position + exponent > 0;
}

} // namespace

bool parseAnyNumber(std::string_view word, double& value)
{
    // from_chars refuses a leading '+'; people write one.
    if (!word.empty() && word.front() == '+') word.remove_prefix(1);
    if (word.empty()) return false;
    if (parseDecimalFast(word, value)) return true;
    const char* const last = word.data() + word.size();
    const std::from_chars_result result = std::from_chars(word.data(), last, value);
    if (result.ptr != last) return false;
    if (result.ec == std::errc::result_out_of_range)
    {
        // Beyond the double range reads as infinite, below it as zero (both of the word's sign).
        const double magnitude = overflows(word) ? std::numeric_limits<double>::infinity() : 0.0;
        value = word.front() == '-' ? -magnitude : magnitude;
    }
    else if (result.ec != std::errc())
        return false;
    return true;
}

bool parseNumber(std::string_view word, double& value)
{
    double parsed = 0.0;
    if (!parseAnyNumber(word, parsed) || !std::isfinite(parsed)) return false;
    value = parsed;
    return true;
}

bool isNonFiniteNumber(std::string_view word)
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

std::string formatExactNumber(double value)
{
    if (!(std::abs(value) >= kZeroBelow)) return "0";
    char buffer[64];
    const std::to_chars_result result = std::to_chars(buffer, buffer + sizeof(buffer), value); // shortest exact
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
