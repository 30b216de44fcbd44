#include <osgActor/io/ActorNumbers>
#include <osgActor/io/ActorSyntax>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <random>
#include <sstream>

using namespace osgActor;

namespace {

std::string parseError(const std::string& text)
{
    std::istringstream in(text);
    std::vector<SyntaxStatement> statements;
    std::string error;
    EXPECT_FALSE(parseSyntax(in, "t.actor", statements, error)) << text;
    EXPECT_TRUE(statements.empty()) << "nothing half-parsed is handed back";
    return error;
}

} // namespace

// --- refusals first ---

TEST(ActorSyntax, AnUnclosedBlockNamesTheLineItOpened)
{
    EXPECT_EQ(parseError("actor a {\n  joint b {\n    offset 1 2 3\n"),
              "t.actor:4: the file ends inside the block opened at line 2");
}

TEST(ActorSyntax, StrayBracesAndStringsAreRefused)
{
    EXPECT_EQ(parseError("a\n}\n"), "t.actor:2: '}' closes no block");
    EXPECT_EQ(parseError("{ a }"), "t.actor:1: '{' must follow a keyword");
    EXPECT_EQ(parseError("\n\"a\" b"), "t.actor:2: a statement must start with a keyword, not the string \"a\"");
    EXPECT_EQ(parseError("a \"open\nb"), "t.actor:1: the string that starts here is not closed on its line");
}

TEST(ActorSyntax, HostileNestingIsRefusedNotOverflowed)
{
    std::string deep;
    for (int i = 0; i < 100000; ++i) deep += "a {";
    EXPECT_NE(parseError(deep).find("nested too deeply"), std::string::npos);
}

TEST(ActorSyntax, NumbersMustBeWholeWordsAndFinite)
{
    double v = 7.0;
    for (const char* bad : {"", "1x", "nan", "NaN", "inf", "-inf", "1e999", "0x10", "1,5", "--1", " 1"})
        EXPECT_FALSE(parseNumber(bad, v)) << "'" << bad << "'";
    EXPECT_EQ(v, 7.0) << "a refused number leaves the value alone";
    for (const char* nonFinite : {"nan", "NaN", "-inf", "+inf", "infinity", "1e999", "-1e999"})
        EXPECT_TRUE(isNonFiniteNumber(nonFinite)) << nonFinite;
    for (const char* other : {"1", "info", "1nan", "", "x"}) EXPECT_FALSE(isNonFiniteNumber(other)) << other;
    ASSERT_TRUE(parseNumber("+2.5e-1", v));
    EXPECT_EQ(v, 0.25);
    ASSERT_TRUE(parseNumber("-3", v));
    EXPECT_EQ(v, -3.0);
}

// --- structure ---

TEST(ActorSyntax, StatementsEndAtNewlinesOrSemicolonsAndNestInBraces)
{
    std::istringstream in("# a comment\nactor \"my actor\" { # trailing comment\n  joint a { offset 1 2 3; dof rx }\n"
                          "  blocked\n}\n");
    std::vector<SyntaxStatement> statements;
    std::string error;
    ASSERT_TRUE(parseSyntax(in, "t.actor", statements, error)) << error;
    ASSERT_EQ(statements.size(), 1u);
    const SyntaxStatement& actor = statements[0];
    EXPECT_EQ(actor.keyword, "actor");
    EXPECT_EQ(actor.line, 2);
    ASSERT_EQ(actor.arguments.size(), 1u);
    EXPECT_EQ(actor.arguments[0].text, "my actor");
    EXPECT_TRUE(actor.arguments[0].quoted);
    ASSERT_EQ(actor.children.size(), 2u);
    const SyntaxStatement& joint = actor.children[0];
    EXPECT_EQ(joint.line, 3);
    ASSERT_EQ(joint.children.size(), 2u);
    EXPECT_EQ(joint.children[0].keyword, "offset");
    ASSERT_EQ(joint.children[0].arguments.size(), 3u);
    EXPECT_EQ(joint.children[0].arguments[2].text, "3");
    EXPECT_EQ(joint.children[1].keyword, "dof");
    EXPECT_EQ(actor.children[1].keyword, "blocked");
    EXPECT_EQ(actor.children[1].line, 4);
}

TEST(ActorSyntax, QuotedNamesKeepEscapesAndRoundTrip)
{
    EXPECT_EQ(quoteIfNeeded("l_elbow"), "l_elbow");
    EXPECT_EQ(quoteIfNeeded("left arm"), "\"left arm\"");
    EXPECT_EQ(quoteIfNeeded(""), "\"\"");
    EXPECT_EQ(quoteIfNeeded("a\"b\\c"), "\"a\\\"b\\\\c\"");
    std::istringstream in("joint " + quoteIfNeeded("a\"b\\c {x}") + "\n");
    std::vector<SyntaxStatement> statements;
    std::string error;
    ASSERT_TRUE(parseSyntax(in, "t.actor", statements, error)) << error;
    EXPECT_EQ(statements[0].arguments[0].text, "a\"b\\c {x}");
}

TEST(ActorSyntax, WritingParsedStatementsGivesTheCanonicalText)
{
    const std::string canonical = "a 1 \"two words\" {\n    b\n    c 3 {\n        d\n    }\n}\ne\n";
    std::istringstream in("a 1 \"two words\" {  b ; c 3 { d } }\n\n e");
    std::vector<SyntaxStatement> statements;
    std::string error;
    ASSERT_TRUE(parseSyntax(in, "t.actor", statements, error)) << error;
    std::ostringstream out;
    writeSyntax(out, statements);
    EXPECT_EQ(out.str(), canonical);
}

TEST(ActorNumbers, FormattingIsAFixedPointOfReading)
{
    EXPECT_EQ(formatNumber(0.1 + 0.2), "0.3");
    EXPECT_EQ(formatNumber(-0.0), "0");
    EXPECT_EQ(formatNumber(1e-13), "0");
    EXPECT_EQ(formatNumber(-1.5), "-1.5");
    EXPECT_EQ(formatNumber(1234567.0), "1234567");
    // Degrees to radians and back, a thousand times over: the text never changes.
    for (int i = -500; i < 500; ++i)
    {
        const std::string text = formatNumber(i * 0.37 + 0.001 * i * i);
        double value = 0.0;
        ASSERT_TRUE(parseNumber(text, value));
        const double radians = value * (3.14159265358979323846 / 180.0);
        EXPECT_EQ(formatNumber(radians * (180.0 / 3.14159265358979323846)), text);
    }
}

TEST(ActorNumbers, RotationsReadAsAnAngleAboutAnAxisScaledToItsLargestComponent)
{
    glm::dquat q;
    AngleAxis zero;
    zero.axis[2] = 0.0;
    EXPECT_FALSE(toQuaternion(zero, q)) << "a zero axis";
    AngleAxis turn;
    turn.degrees = 90.0;
    turn.axis[0] = 0.0;
    turn.axis[1] = 0.0;
    turn.axis[2] = 2.0; // any length
    ASSERT_TRUE(toQuaternion(turn, q));
    EXPECT_NEAR(q.w, std::sqrt(0.5), 1e-15);
    EXPECT_NEAR(q.z, std::sqrt(0.5), 1e-15);
    const AngleAxis back = toAngleAxis(-q); // the same rotation with w < 0
    EXPECT_NEAR(back.degrees, 90.0, 1e-12);
    EXPECT_EQ(back.axis[2], 1.0);
    EXPECT_EQ(back.axis[0], 0.0);
    EXPECT_TRUE(isIdentityRotation(glm::dquat(1.0, 0.0, 0.0, 0.0)));
    EXPECT_FALSE(isIdentityRotation(q));
    // An oblique axis keeps its written ratios through quaternion and back.
    AngleAxis oblique;
    oblique.degrees = 33.3;
    oblique.axis[0] = 1.0;
    oblique.axis[1] = -0.25;
    oblique.axis[2] = 0.7;
    ASSERT_TRUE(toQuaternion(oblique, q));
    const AngleAxis again = toAngleAxis(q);
    EXPECT_EQ(formatNumber(again.degrees), "33.3");
    EXPECT_EQ(formatNumber(again.axis[0]), "1");
    EXPECT_EQ(formatNumber(again.axis[1]), "-0.25");
    EXPECT_EQ(formatNumber(again.axis[2]), "0.7");
}

TEST(ParseNumber, RefusesWhatIsNotADecimalNumber)
{
    double value = 0.0;
    for (const char* bad : {"", "+", "-", ".", "e5", "1e", "1e+", "--1", "1.2.3", "0x10", "1,5", "12a", "nan", "NaN",
                            "inf", "-inf", "1e400", "-1e999"})
        EXPECT_FALSE(parseNumber(bad, value)) << bad;
}

TEST(ParseNumber, ReadsTheFormsRealFilesUse)
{
    const std::pair<const char*, double> cases[] = {
        {".0083333", 0.0083333}, {"-0.000000", -0.0},     {"1e-014", 1e-14},   {"9.27E-16", 9.27e-16},
        {"+90", 90.0},           {"-.25", -0.25},         {"1.", 1.0},         {"007", 7.0},
        {"27.973049", 27.973049}, {"-179.999999", -179.999999}, {"3.14159265358979323846", 3.14159265358979323846},
        {"1e-300", 1e-300},      {"123456789012345678901234", 123456789012345678901234.0}};
    for (const auto& c : cases)
    {
        double value = 1.0;
        ASSERT_TRUE(parseNumber(c.first, value)) << c.first;
        EXPECT_EQ(value, c.second) << c.first;
    }
}

TEST(ParseNumber, AgreesWithStrtodToTheBit)
{
    std::mt19937_64 random(7);
    std::uniform_real_distribution<double> mantissa(-1000.0, 1000.0);
    std::uniform_int_distribution<int> digits(0, 17);
    char text[64];
    for (int i = 0; i < 20000; ++i)
    {
        std::snprintf(text, sizeof(text), "%.*f", digits(random), mantissa(random));
        double value = 0.0;
        ASSERT_TRUE(parseNumber(text, value)) << text;
        EXPECT_EQ(value, std::strtod(text, nullptr)) << text;
        std::snprintf(text, sizeof(text), "%.*e", digits(random), mantissa(random) * 1e-5);
        ASSERT_TRUE(parseNumber(text, value)) << text;
        EXPECT_EQ(value, std::strtod(text, nullptr)) << text;
    }
}

TEST(ParseNumber, NonFiniteWordsAreNumbersButNotFiniteOnes)
{
    // Out of the double range reads as an infinity of its sign, so messages can say "not finite".
    double value = 0.0;
    ASSERT_TRUE(parseAnyNumber("1e999", value));
    EXPECT_EQ(value, std::numeric_limits<double>::infinity());
    ASSERT_TRUE(parseAnyNumber("-1e999", value));
    EXPECT_EQ(value, -std::numeric_limits<double>::infinity());
    ASSERT_TRUE(parseAnyNumber("nan", value));
    EXPECT_TRUE(std::isnan(value));
    for (const char* word : {"nan", "inf", "-inf", "1e999"})
    {
        EXPECT_TRUE(isNonFiniteNumber(word)) << word;
        EXPECT_FALSE(parseNumber(word, value)) << word;
    }
    for (const char* word : {"12", "+1.5e3", "x", "", "1e-400"}) EXPECT_FALSE(isNonFiniteNumber(word)) << word;
}

TEST(ParseNumber, BelowTheDoubleRangeReadsAsZeroAboveItAsInfinity)
{
    // from_chars says "out of range" for both; the position of the first significant digit tells which.
    const std::pair<const char*, double> cases[] = {
        {"1e-400", 0.0},      {"-1e-400", -0.0},   {"0.0001e-330", 0.0}, {"123456e-410", 0.0},
        {"1e400", HUGE_VAL},  {"-12.5e400", -HUGE_VAL}, {"0.001e312", HUGE_VAL}, {"00000.1e309", 1e308}};
    for (const auto& c : cases)
    {
        double value = 7.0;
        ASSERT_TRUE(parseAnyNumber(c.first, value)) << c.first;
        EXPECT_EQ(value, c.second) << c.first;
        EXPECT_EQ(std::signbit(value), std::signbit(c.second)) << c.first;
    }
    double value = 7.0;
    EXPECT_TRUE(parseNumber("1e-400", value));
    EXPECT_EQ(value, 0.0);
    EXPECT_FALSE(parseNumber("1e400", value));
}
