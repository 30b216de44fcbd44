#include <osgActor/text/TextLines>

#include <gtest/gtest.h>

#include <sstream>

using namespace osgActor;

namespace {

std::string errorOf(const std::string& text)
{
    std::istringstream in(text);
    return TextLines(in, "t.txt").error();
}

} // namespace

TEST(TextLines, AControlCharacterIsAnErrorNamingItsLine)
{
    EXPECT_EQ(errorOf(std::string("a b\nc\0d\n", 8)),
              "t.txt:2: a control character (0x00) in the text: names and words hold printable characters only (a "
              "binary or damaged file?)");
    EXPECT_EQ(errorOf("a\r\nb\rc\x1b[0m"), errorOf("a\nb\nc\x1b[0m")) << "every line end counts once";
    EXPECT_NE(errorOf("a\nb\nc\x1b[0m").find("t.txt:3: a control character (0x1B)"), std::string::npos);
    EXPECT_NE(errorOf("name\x7f").find("(0x7F)"), std::string::npos);
    EXPECT_NE(errorOf("a\fb").find("(0x0C)"), std::string::npos);
    EXPECT_EQ(errorOf("\ttabs,\tspaces and line ends\r\n are text\n"), "");
    EXPECT_EQ(errorOf("caf\xc3\xa9 \xe2\x82\xac"), "") << "UTF-8 is text";
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
    EXPECT_EQ(text.endLineNumber(), 5u);
}

TEST(TextLines, TheEndOfTheTextIsOnTheLineAfterAFinalLineEnd)
{
    std::istringstream ended("a\nb\n"), open("a\nb");
    EXPECT_EQ(TextLines(ended, "t").endLineNumber(), 3u);
    EXPECT_EQ(TextLines(open, "t").endLineNumber(), 2u);
}

TEST(TextLines, SkipsAByteOrderMarkAndJoinsTheRestOfALine)
{
    std::istringstream in("\xEF\xBB\xBFJOINT left   upper\tarm\nnext");
    TextLines text(in, "t.txt");
    ASSERT_TRUE(text.nextLine());
    std::string_view token;
    ASSERT_TRUE(text.nextToken(token));
    EXPECT_EQ(token, "JOINT");
    EXPECT_EQ(text.restOfLine(), "left upper arm");
    ASSERT_TRUE(text.nextToken(token));
    EXPECT_EQ(token, "next");
    EXPECT_EQ(text.lineNumber(), 2u);
    EXPECT_TRUE(text.atEnd());
}

TEST(TextLines, WordsCompareWithoutCaseInAscii)
{
    EXPECT_TRUE(sameWord("Xrotation", "XROTATION"));
    EXPECT_FALSE(sameWord("Xrotation", "Xrotatio"));
    EXPECT_FALSE(sameWord("\xc3\xa9", "\xc3\x89")) << "only ASCII letters fold";
}

namespace {

/** A stream buffer that cannot seek, as a pipe's. */
class UnseekableBuffer : public std::streambuf
{
public:
    explicit UnseekableBuffer(std::string text) : _text(std::move(text))
    {
        setg(_text.data(), _text.data(), _text.data() + _text.size());
    }

private:
    std::string _text;
};

std::vector<std::string> allTokens(TextLines& text)
{
    std::vector<std::string> tokens;
    std::string_view token;
    while (text.nextToken(token)) tokens.push_back(std::string(token));
    return tokens;
}

} // namespace

TEST(TextLines, ReadsTheRestOfAStreamFromWhereItStandsWhetherItCanSeekOrNot)
{
    const std::vector<std::string> expected{"b", "c", "d"};
    std::istringstream seekable("skipped\nb c\nd\n");
    std::string skipped;
    std::getline(seekable, skipped);
    TextLines fromTheMiddle(seekable, "t.txt");
    EXPECT_EQ(allTokens(fromTheMiddle), expected);
    EXPECT_EQ(fromTheMiddle.bytesAfterLine(), 0u);

    UnseekableBuffer buffer("b c\nd\n");
    std::istream unseekable(&buffer);
    TextLines fromAPipe(unseekable, "t.txt");
    EXPECT_EQ(fromAPipe.bytesAfterLine(), 6u) << "nothing read yet: all of it";
    ASSERT_TRUE(fromAPipe.nextLine());
    EXPECT_EQ(fromAPipe.bytesAfterLine(), 2u) << "after \"b c\\n\"";
    EXPECT_EQ(allTokens(fromAPipe), (std::vector<std::string>{"b", "c", "d"}));
}
