#include <osgActor/io/ActorSyntax>

#include <gtest/gtest.h>

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
