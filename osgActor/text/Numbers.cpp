#include <osgActor/text/Numbers>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <limits>

namespace osgActor {

namespace {

/** Exact powers of ten up to 1e22, the largest a double holds exactly. */
const double kPowersOfTen[] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,  1e8,  1e9,  1e10, 1e11,
                               1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};

bool isDigit(char c) { return c >= '0' && c <= '9'; }

/** Clinger's fast path: a decimal whose digits fit in 53 bits, scaled by at most 10^22, is one correctly rounded
  * multiplication or division of two exact doubles, so the result equals std::from_chars'. Mocap numbers
  * ("-0.000000", "27.973049", ".0083333", "1e-014") nearly all take it; false sends the rest to std::from_chars.
  * The word has no leading '+'. */
bool readDecimalFast(std::string_view word, double& value)
{
    const char* p = word.data();
    const char* const end = p + word.size();
    const bool negative = p != end && *p == '-';
    if (negative) ++p;
    std::uint64_t mantissa = 0;
    int digits = 0;   // significant digits kept in mantissa
    int exponent = 0; // power of ten to apply
    bool any = false;
    for (; p != end && isDigit(*p); ++p, any = true)
    {
        if (mantissa == 0 && *p == '0') continue; // leading zeros are not significant
        if (++digits > 19) return false;
        mantissa = mantissa * 10 + static_cast<unsigned>(*p - '0');
    }
    if (p != end && *p == '.')
    {
        for (++p; p != end && isDigit(*p); ++p, any = true)
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
        if (p == end || !isDigit(*p)) return false;
        int written = 0;
        for (; p != end && isDigit(*p); ++p)
        {
            if (written > 1000) return false;
            written = written * 10 + (*p - '0');
        }
        exponent += negativeExponent ? -written : written;
    }
    if (p != end) return false;
    if (mantissa == 0)
    {
        value = negative ? -0.0 : 0.0;
        return true;
    }
    if (mantissa > (std::uint64_t(1) << 53) || exponent < -22 || exponent > 22) return false;
    const double m = static_cast<double>(mantissa);
    value = exponent < 0 ? m / kPowersOfTen[-exponent] : m * kPowersOfTen[exponent];
    if (negative) value = -value;
    return true;
}

/** For a decimal word std::from_chars found out of range: whether it is too large (an overflow), not too small (an
  * underflow). The decimal point of its first significant digit, shifted by the exponent, says which. */
bool overflows(std::string_view word)
{
    std::size_t i = word.front() == '-' ? 1 : 0;
    long position = 0; // the power of ten just above the first significant digit
    bool significant = false;
    for (; i < word.size() && isDigit(word[i]); ++i)
        if (significant || word[i] != '0')
        {
            significant = true;
            ++position;
        }
    if (i < word.size() && word[i] == '.')
        for (++i; i < word.size() && isDigit(word[i]); ++i)
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
        for (; i < word.size() && isDigit(word[i]) && exponent < 100000; ++i)
            exponent = exponent * 10 + (word[i] - '0');
        if (negative) exponent = -exponent;
    }
    return position + exponent > 0;
}

/** Sign-exact equality: -0 and 0 differ, as the bits a writer must give back do. */
bool sameDouble(double a, double b) { return a == b && std::signbit(a) == std::signbit(b); }

/** The number of characters formatNumber() writes for value. */
std::size_t textLength(double value)
{
    char buffer[32];
    return static_cast<std::size_t>(std::to_chars(buffer, buffer + sizeof(buffer), value).ptr - buffer);
}

/** How far formatInverse() looks for a number that converts to the stored value: a few steps for the first one
  * (the conversion and its inverse round once each), many for the run of numbers that convert to the same value
  * (a conversion that shrinks, such as degrees to radians, maps dozens of subnormal numbers onto one). */
constexpr int kFirstSearchSteps = 4;
constexpr int kRunSearchSteps = 256;

} // namespace

NumberWord readNumber(std::string_view word, double& value)
{
    // from_chars refuses a leading '+'; people write one (but not "+-1" or "++1").
    if (!word.empty() && word.front() == '+')
    {
        word.remove_prefix(1);
        if (!word.empty() && (word.front() == '+' || word.front() == '-')) return NumberWord::NotANumber;
    }
    if (word.empty()) return NumberWord::NotANumber;
    double parsed = 0.0;
    if (readDecimalFast(word, parsed))
    {
        value = parsed;
        return NumberWord::Finite;
    }
    const char* const last = word.data() + word.size();
    const std::from_chars_result result = std::from_chars(word.data(), last, parsed);
    if (result.ptr != last) return NumberWord::NotANumber;
    if (result.ec == std::errc::result_out_of_range)
        return overflows(word) ? NumberWord::NonFinite : NumberWord::TooSmall;
    if (result.ec != std::errc()) return NumberWord::NotANumber;
    if (!std::isfinite(parsed)) return NumberWord::NonFinite;
    value = parsed;
    return NumberWord::Finite;
}

bool parseNumber(std::string_view word, double& value) { return readNumber(word, value) == NumberWord::Finite; }

std::string numberProblem(std::string_view word)
{
    double value = 0.0;
    const std::string quoted = "'" + std::string(word) + "'";
    switch (readNumber(word, value))
    {
    case NumberWord::Finite: return std::string();
    case NumberWord::NonFinite: return quoted + " is not a finite number";
    case NumberWord::TooSmall: return quoted + " is too small for a double (it would read as 0)";
    case NumberWord::NotANumber: break;
    }
    return quoted + " is not a number";
}

bool parseCount(std::string_view word, unsigned long& value)
{
    if (word.empty() || !isDigit(word.front())) return false;
    const char* const last = word.data() + word.size();
    unsigned long parsed = 0;
    const std::from_chars_result result = std::from_chars(word.data(), last, parsed);
    if (result.ec != std::errc() || result.ptr != last) return false;
    value = parsed;
    return true;
}

void appendNumber(std::string& text, double value)
{
    char buffer[32];
    const std::to_chars_result written = std::to_chars(buffer, buffer + sizeof(buffer), value); // shortest exact
    text.append(buffer, written.ptr);
}

std::string formatNumber(double value)
{
    std::string text;
    appendNumber(text, value);
    return text;
}

std::string formatInverse(double stored, double guess, double (*convert)(double))
{
    std::string text;
    if (formatExactInverse(stored, guess, convert, text)) return text;
    // An inverse that overflows (the largest degrees times pi / 180, and back) is the largest double at most.
    if (std::isfinite(stored) && !std::isfinite(guess))
        guess = std::copysign(std::numeric_limits<double>::max(), guess);
    return formatNumber(guess);
}

bool formatExactInverse(double stored, double guess, double (*convert)(double), std::string& text)
{
    double written = 0.0;
    if (!findExactInverse(stored, guess, convert, written)) return false;
    text = formatNumber(written);
    return true;
}

bool findExactInverse(double stored, double guess, double (*convert)(double), double& written)
{
    if (!std::isfinite(stored)) return false;
    const double infinity = std::numeric_limits<double>::infinity();
    if (!std::isfinite(guess)) guess = std::copysign(std::numeric_limits<double>::max(), guess);
    // A number near guess that converts to stored, guess itself first.
    double found = guess;
    bool hit = sameDouble(convert(guess), stored);
    double below = guess, above = guess;
    for (int step = 0; step < kFirstSearchSteps && !hit; ++step)
    {
        below = std::nextafter(below, -infinity);
        above = std::nextafter(above, infinity);
        if (sameDouble(convert(below), stored)) found = below, hit = true;
        else if (sameDouble(convert(above), stored)) found = above, hit = true;
    }
    if (!hit) return false;
    // Every number of the run that converts to stored reads back as stored: the shortest of them is written.
    double best = found;
    std::size_t bestLength = textLength(found);
    for (const double direction : {-infinity, infinity})
    {
        double x = found;
        for (int step = 0; step < kRunSearchSteps; ++step)
        {
            x = std::nextafter(x, direction);
            if (!std::isfinite(x) || !sameDouble(convert(x), stored)) break;
            const std::size_t length = textLength(x);
            if (length < bestLength) best = x, bestLength = length;
        }
    }
    written = best;
    return true;
}

double shortestNear(double value, int steps)
{
    if (!std::isfinite(value)) return value;
    double best = value;
    std::size_t bestLength = textLength(value);
    double below = value, above = value;
    for (int step = 0; step < steps; ++step)
    {
        below = std::nextafter(below, -std::numeric_limits<double>::infinity());
        above = std::nextafter(above, std::numeric_limits<double>::infinity());
        for (const double candidate : {below, above})
        {
            const std::size_t length = std::isfinite(candidate) ? textLength(candidate) : bestLength;
            if (length < bestLength) best = candidate, bestLength = length;
        }
    }
    return best;
}

double roundToSignificantDigits(double value, int digits)
{
    if (!std::isfinite(value)) return value;
    char buffer[64];
    const std::to_chars_result written = std::to_chars(buffer, buffer + sizeof(buffer), value,
                                                       std::chars_format::scientific, std::max(0, digits - 1));
    double rounded = value;
    // Rounding a finite double to fewer digits may reach beyond the largest double; then it stays as it is.
    if (!parseNumber(std::string_view(buffer, static_cast<std::size_t>(written.ptr - buffer)), rounded)) return value;
    return rounded;
}

double doubleFromFloatText(float value)
{
    if (!std::isfinite(value)) return value;
    char buffer[32];
    const std::to_chars_result written = std::to_chars(buffer, buffer + sizeof(buffer), value);
    double result = value;
    // The shortest text of a finite float always reads as a double; the float's own value is the fallback all
    // the same.
    if (!parseNumber(std::string_view(buffer, static_cast<std::size_t>(written.ptr - buffer)), result)) return value;
    return result;
}

} // namespace osgActor
