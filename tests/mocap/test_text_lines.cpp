#include <osgActor/mocap/TextLines>

#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <random>
#include <sstream>

using namespace osgActor;

TEST(ParseNumberToken, RefusesWhatIsNotADecimalNumber)
{
    double value = 0.0;
    for (const char* bad : {"", "+", "-", ".", "e5", "1e", "1e+", "--1", "1.2.3", "0x10", "1,5", "12a", "nan", "NaN",
                            "inf", "-inf", "1e400", "-1e999"})
        EXPECT_FALSE(parseNumberToken(bad, value)) << bad;
}

TEST(ParseNumberToken, ReadsTheFormsRealFilesUse)
{
    const std::pair<const char*, double> cases[] = {
        {".0083333", 0.0083333}, {"-0.000000", -0.0},     {"1e-014", 1e-14},   {"9.27E-16", 9.27e-16},
        {"+90", 90.0},           {"-.25", -0.25},         {"1.", 1.0},         {"007", 7.0},
        {"27.973049", 27.973049}, {"-179.999999", -179.999999}, {"3.14159265358979323846", 3.14159265358979323846},
        {"1e-300", 1e-300},      {"123456789012345678901234", 123456789012345678901234.0}};
    for (const auto& c : cases)
    {
        double value = 1.0;
        ASSERT_TRUE(parseNumberToken(c.first, value)) << c.first;
        EXPECT_EQ(value, c.second) << c.first;
    }
}

TEST(ParseNumberToken, AgreesWithStrtodToTheBit)
{
    std::mt19937_64 random(7);
    std::uniform_real_distribution<double> mantissa(-1000.0, 1000.0);
    std::uniform_int_distribution<int> digits(0, 17);
    char text[64];
    for (int i = 0; i < 20000; ++i)
    {
        std::snprintf(text, sizeof(text), "%.*f", digits(random), mantissa(random));
        double value = 0.0;
        ASSERT_TRUE(parseNumberToken(text, value)) << text;
        EXPECT_EQ(value, std::strtod(text, nullptr)) << text;
        std::snprintf(text, sizeof(text), "%.*e", digits(random), mantissa(random) * 1e-5);
        ASSERT_TRUE(parseNumberToken(text, value)) << text;
        EXPECT_EQ(value, std::strtod(text, nullptr)) << text;
    }
}

TEST(TextLines, SplitsLinesAndTokensWhateverTheLineEnds)
{
    std::istringstream in("a b\r\n\tc  \rd\n\ne");
    TextLines text(in, "t.txt");
    std::vector<std::string> seen;
    std::string_view token;
    while (text.nextToken(token)) seen.push_back(std::string(token) + "@" + std::to_string(text.lineNumber()));
    EXPECT_EQ(seen, (std::vector<std::string>{"a@1", "b@1", "c@2", "d@3", "e@5"}));
    EXPECT_EQ(text.where(), "t.txt:5: ");
}
