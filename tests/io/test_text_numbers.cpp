#include <osgActor/text/Degrees>
#include <osgActor/text/Numbers>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <random>

using namespace osgActor;

namespace {

/** Bitwise equality: -0 differs from 0. */
bool sameBits(double a, double b) { return std::memcmp(&a, &b, sizeof(double)) == 0; }

double read(const std::string& text)
{
    double value = std::numeric_limits<double>::quiet_NaN();
    EXPECT_TRUE(parseNumber(text, value)) << text;
    return value;
}

/** A decimal of 0 to 17 digits after the point, as files write them, in [low, high). */
std::string randomDecimal(std::mt19937_64& random, double low, double high)
{
    std::uniform_real_distribution<double> value(low, high);
    std::uniform_int_distribution<int> digits(0, 17);
    char text[64];
    std::snprintf(text, sizeof(text), "%.*f", digits(random), value(random));
    return text;
}

} // namespace

// --- refusals first ---

TEST(Numbers, RefusesWhatIsNotADecimalNumber)
{
    double value = 7.0;
    for (const char* bad : {"", "+", "-", ".", "e5", "1e", "1e+", "--1", "+-1", "++1", "1.2.3", "0x10", "1,5", "12a",
                            " 1", "1 ", "1_000"})
    {
        EXPECT_EQ(readNumber(bad, value), NumberWord::NotANumber) << "'" << bad << "'";
        EXPECT_EQ(numberProblem(bad), "'" + std::string(bad) + "' is not a number");
    }
    EXPECT_EQ(value, 7.0) << "a refused number leaves the value alone";
}

TEST(Numbers, RefusesNonFiniteNumbersAndMagnitudesBeyondTheDoubleRange)
{
    double value = 7.0;
    for (const char* word : {"nan", "NaN", "inf", "-inf", "+inf", "infinity", "1e400", "-12.5e400", "0.001e312",
                             "1.8e308"})
    {
        EXPECT_EQ(readNumber(word, value), NumberWord::NonFinite) << word;
        EXPECT_FALSE(parseNumber(word, value)) << word;
        EXPECT_EQ(numberProblem(word), "'" + std::string(word) + "' is not a finite number");
    }
    EXPECT_EQ(value, 7.0);
}

TEST(Numbers, RefusesANumberSoSmallItWouldReadAsZero)
{
    // A file that says 1e-400 does not mean 0; the nearest double is 0, so the number cannot be held.
    double value = 7.0;
    for (const char* word : {"1e-400", "-1e-400", "0.0001e-330", "123456e-410", "2e-324"})
    {
        EXPECT_EQ(readNumber(word, value), NumberWord::TooSmall) << word;
        EXPECT_EQ(numberProblem(word), "'" + std::string(word) + "' is too small for a double (it would read as 0)");
    }
    EXPECT_EQ(value, 7.0);
    EXPECT_TRUE(sameBits(read("0e-999"), 0.0)) << "zero written small is zero";
    EXPECT_TRUE(sameBits(read("-0e-999"), -0.0));
    EXPECT_TRUE(sameBits(read("3e-324"), 5e-324)) << "rounds to the smallest subnormal, not to 0";
}

TEST(Numbers, CountsAreDigitsOnlyWithinAnUnsignedLong)
{
    unsigned long value = 7;
    for (const char* bad : {"", "-1", "+1", "1.0", "1e3", " 1", "18446744073709551616"})
        EXPECT_FALSE(parseCount(bad, value)) << bad;
    EXPECT_EQ(value, 7u);
    ASSERT_TRUE(parseCount("007", value));
    EXPECT_EQ(value, 7u);
    ASSERT_TRUE(parseCount("18446744073709551615", value));
    EXPECT_EQ(value, std::numeric_limits<unsigned long>::max());
}

// --- reading ---

TEST(Numbers, ReadsTheFormsRealFilesUse)
{
    const std::pair<const char*, double> cases[] = {
        {".0083333", 0.0083333}, {"-0.000000", -0.0},     {"1e-014", 1e-14},   {"9.27E-16", 9.27e-16},
        {"+90", 90.0},           {"-.25", -0.25},         {"1.", 1.0},         {"007", 7.0},
        {"27.973049", 27.973049}, {"-179.999999", -179.999999}, {"3.14159265358979323846", 3.14159265358979323846},
        {"1e-300", 1e-300},      {"123456789012345678901234", 123456789012345678901234.0},
        {"00000.1e309", 1e308},  {"1E+300", 1e300}};
    for (const auto& c : cases)
    {
        double value = 1.0;
        ASSERT_EQ(readNumber(c.first, value), NumberWord::Finite) << c.first;
        EXPECT_TRUE(sameBits(value, c.second)) << c.first;
    }
}

TEST(Numbers, ReadingAgreesWithStrtodToTheBit)
{
    std::mt19937_64 random(7);
    std::uniform_real_distribution<double> mantissa(-1000.0, 1000.0);
    std::uniform_int_distribution<int> digits(0, 17);
    for (int i = 0; i < 20000; ++i)
    {
        const std::string fixed = randomDecimal(random, -1000.0, 1000.0);
        EXPECT_TRUE(sameBits(read(fixed), std::strtod(fixed.c_str(), nullptr))) << fixed;
        char text[64];
        std::snprintf(text, sizeof(text), "%.*e", digits(random), mantissa(random) * 1e-5);
        EXPECT_TRUE(sameBits(read(text), std::strtod(text, nullptr))) << text;
    }
}

// --- writing ---

TEST(Numbers, WritesTheShortestTextThatReadsBackAsTheSameDouble)
{
    EXPECT_EQ(formatNumber(0.1 + 0.2), "0.30000000000000004");
    EXPECT_EQ(formatNumber(0.3), "0.3");
    EXPECT_EQ(formatNumber(-0.0), "-0");
    EXPECT_EQ(formatNumber(0.0), "0");
    EXPECT_EQ(formatNumber(-1.5), "-1.5");
    EXPECT_EQ(formatNumber(1234567.0), "1234567");
    EXPECT_EQ(formatNumber(1e-300), "1e-300");
    EXPECT_EQ(formatNumber(-1e300), "-1e+300");
    EXPECT_EQ(formatNumber(5e-324), "5e-324");
    EXPECT_EQ(formatNumber(std::numeric_limits<double>::max()), "1.7976931348623157e+308");
    EXPECT_EQ(formatNumber(std::numeric_limits<double>::infinity()), "inf") << "which every reader refuses";
    std::string text = "x ";
    appendNumber(text, 2.5);
    EXPECT_EQ(text, "x 2.5");
}

TEST(Numbers, EveryDoubleReadsBackFromItsTextBitForBit)
{
    // Random bit patterns cover every exponent, subnormals and both zeros.
    std::mt19937_64 random(11);
    for (int i = 0; i < 100000; ++i)
    {
        const std::uint64_t bits = random();
        double value;
        std::memcpy(&value, &bits, sizeof(value));
        if (!std::isfinite(value)) continue;
        const std::string text = formatNumber(value);
        double back = 0.0;
        ASSERT_EQ(readNumber(text, back), NumberWord::Finite) << text;
        EXPECT_TRUE(sameBits(back, value)) << text;
    }
    for (const double edge : {-0.0, 4.9406564584124654e-324, 2.2250738585072009e-308, 2.2250738585072014e-308,
                              -std::numeric_limits<double>::max(), 1e-300, 1e300})
        EXPECT_TRUE(sameBits(read(formatNumber(edge)), edge)) << edge;
}

TEST(Numbers, AFloatReadsAsTheDoubleOfItsShortestText)
{
    EXPECT_EQ(doubleFromFloatText(0.3f), 0.3);
    EXPECT_EQ(doubleFromFloatText(-1.25f), -1.25);
    EXPECT_EQ(doubleFromFloatText(1e-45f), 1e-45);
    EXPECT_TRUE(std::isinf(doubleFromFloatText(std::numeric_limits<float>::infinity())));
}

// --- conversions: what a reader converted, the writer writes so that the same conversion gives it back ---

TEST(Degrees, AngleReadFromAFileIsWrittenAsDegreesThatReadBackToTheSameRadians)
{
    std::mt19937_64 random(3);
    for (int i = 0; i < 20000; ++i)
    {
        const std::string text = randomDecimal(random, -720.0, 720.0);
        const double radians = radiansFromDegrees(read(text));
        const std::string written = formatDegrees(radians);
        EXPECT_TRUE(sameBits(radiansFromDegrees(read(written)), radians)) << text << " written " << written;
        // The file's own number converts to these radians too, so the text is never longer than its shortest form.
        EXPECT_LE(written.size(), formatNumber(read(text)).size()) << text << " written " << written;
    }
}

TEST(Degrees, RoundAnglesStayRoundAndEdgeValuesSurvive)
{
    for (const char* round : {"90", "45", "30", "-180", "0.1", "33.3", "-0", "0"})
        EXPECT_EQ(formatDegrees(radiansFromDegrees(read(round))), round);
    for (const double degrees : {1e-300, -1e-300, 1e300, 1e-320, 5e-324, 2.5e-322, std::numeric_limits<double>::max(),
                                 -std::numeric_limits<double>::max(), 2.2250738585072014e-308})
    {
        const double radians = radiansFromDegrees(degrees);
        const std::string written = formatDegrees(radians);
        EXPECT_TRUE(sameBits(radiansFromDegrees(read(written)), radians)) << degrees << " written " << written;
    }
    EXPECT_EQ(formatDegrees(radiansFromDegrees(1e-320)), "1e-320") << "the shortest of the subnormals that give it";
}

TEST(Degrees, AnAngleFromNoFileIsWrittenWithinARoundingStep)
{
    // One radian is no double number of degrees times pi / 180 exactly; the nearest degrees are written.
    const double back = radiansFromDegrees(read(formatDegrees(1.0)));
    EXPECT_NEAR(back, 1.0, 2e-16);
    EXPECT_EQ(read(formatDegrees(std::numeric_limits<double>::max())), std::numeric_limits<double>::max())
        << "degrees beyond the double range are written as the largest double";
}

TEST(Numbers, AnInverseConversionFindsTheFrameTimeOfAFrameRate)
{
    double (*rateOf)(double) = [](double frameTime) { return 1.0 / frameTime; };
    for (const char* frameTime : {"0.0083333", "0.033333", "0.008333333333", "1", "1e-300", "1e300"})
    {
        const double rate = rateOf(read(frameTime));
        const std::string written = formatInverse(rate, 1.0 / rate, rateOf);
        EXPECT_TRUE(sameBits(rateOf(read(written)), rate)) << frameTime << " written " << written;
        EXPECT_LE(written.size(), formatNumber(read(frameTime)).size()) << frameTime << " written " << written;
    }
}

TEST(Angles, AreDegreesOrRadiansWithTheirSuffix)
{
    double radians = 7.0;
    EXPECT_EQ(readAngle("90", radians), NumberWord::Finite);
    EXPECT_EQ(radians, radiansFromDegrees(90.0));
    EXPECT_EQ(readAngle("1.5rad", radians), NumberWord::Finite);
    EXPECT_EQ(radians, 1.5);
    radians = 7.0;
    for (const char* bad : {"rad", "1 rad", "1.5deg", "1.5radians", "radx"})
    {
        EXPECT_EQ(readAngle(bad, radians), NumberWord::NotANumber) << bad;
        EXPECT_NE(angleProblem(bad).find("is not a number"), std::string::npos) << bad;
    }
    EXPECT_EQ(readAngle("infrad", radians), NumberWord::NonFinite);
    EXPECT_EQ(angleProblem("1e-400rad"), "'1e-400rad': '1e-400' is too small for a double (it would read as 0)");
    EXPECT_EQ(radians, 7.0);
}

TEST(Angles, AreWrittenInDegreesWhenExactAndInRadiansOtherwise)
{
    EXPECT_EQ(formatAngle(radiansFromDegrees(90.0)), "90");
    EXPECT_EQ(formatAngle(radiansFromDegrees(-1e-300)), "-1e-300");
    EXPECT_EQ(formatAngle(1.0), "57.29577951308232") << "57.29577951308232 degrees are exactly 1 radian";
    // About one radian in eleven is no double number of degrees times pi / 180: it is written in radians, exactly.
    EXPECT_EQ(formatAngle(0.7568359910159614), "0.7568359910159614rad");
    std::mt19937_64 random(9);
    std::uniform_real_distribution<double> angle(-10.0, 10.0);
    for (int i = 0; i < 10000; ++i)
    {
        const double radians = angle(random);
        double back = 0.0;
        ASSERT_EQ(readAngle(formatAngle(radians), back), NumberWord::Finite) << formatAngle(radians);
        EXPECT_TRUE(sameBits(back, radians)) << formatAngle(radians);
    }
}
