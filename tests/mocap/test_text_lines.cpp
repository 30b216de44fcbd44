#include <osgActor/mocap/TextLines>

#include <gtest/gtest.h>

#include <sstream>

using namespace osgActor;

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
