// SyntaxWriter: the .actor syntax written a statement at a time, as writeActor() and writeSyntax() write it.
#include <osgActor/io/SyntaxWriter>
#include <osgActor/text/Degrees>

#include <gtest/gtest.h>

#include <sstream>

using namespace osgActor;

TEST(SyntaxWriter, AStatementWithoutChildrenIsOneLineAndOneWithChildrenOpensItsBlockAtTheFirst)
{
    std::ostringstream out;
    {
        SyntaxWriter w(out);
        w.begin("joint").name("hip");
        w.begin("dof").word("rx").end();
        w.begin("joint").name("knee");
        w.begin("hidden").end();
        w.end();
        w.begin("joint").name("toe").end();
        w.end();
        w.begin("blocked").end();
    }
    EXPECT_EQ(out.str(), "joint hip {\n"
                         "    dof rx\n"
                         "    joint knee {\n"
                         "        hidden\n"
                         "    }\n"
                         "    joint toe\n"
                         "}\n"
                         "blocked\n");
}

TEST(SyntaxWriter, AnOpenedBlockIsWrittenEvenWithNothingInIt)
{
    std::ostringstream out;
    {
        SyntaxWriter w(out, 1);
        w.begin("actor").name("a").openBlock().end();
        w.begin("clip").name("c").openBlock();
        w.begin("frame_rate").number(30).end();
        w.end();
    }
    EXPECT_EQ(out.str(), "    actor a {\n    }\n    clip c {\n        frame_rate 30\n    }\n");
}

TEST(SyntaxWriter, NamesAreQuotedOnlyWhenTheyMustBeStringsAlwaysAndNumbersAndAnglesAreShortestExact)
{
    std::ostringstream out;
    {
        SyntaxWriter w(out);
        w.begin("s").name("l_knee").name("left knee").name("").name("a\"b\\c").quoted("walk.bvh").end();
        w.begin("n").number(0.1).number(-0.0).number(1e-300).number(5e-324).number(1.0 / 3.0).end();
        w.begin("a").angle(radiansFromDegrees(90.0)).angle(1.0).angle(0.7568359910159614).end();
    }
    EXPECT_EQ(out.str(), "s l_knee \"left knee\" \"\" \"a\\\"b\\\\c\" \"walk.bvh\"\n"
                         "n 0.1 -0 1e-300 5e-324 0.3333333333333333\n"
                         "a 90 57.29577951308232 0.7568359910159614rad\n");
}

TEST(SyntaxWriter, TheTextReachesTheStreamWhileStatementsAreStillBeingWrittenWholeAndInOrder)
{
    std::ostringstream out;
    std::string expected;
    bool streamedEarly = false;
    {
        SyntaxWriter w(out);
        w.begin("actor").name("large");
        for (int j = 0; j < 20000; ++j)
        {
            w.begin("joint").name("j" + std::to_string(j)).number(j * 0.1).end();
            expected += "    joint j" + std::to_string(j) + " " + formatNumber(j * 0.1) + "\n";
            streamedEarly = streamedEarly || !out.str().empty();
        }
        w.end();
    }
    EXPECT_TRUE(streamedEarly) << "the writer keeps a piece of the text, not all of it";
    EXPECT_EQ(out.str(), "actor large {\n" + expected + "}\n");
}

TEST(SyntaxWriter, WholeStatementsAreWrittenWithTheirBlocksAndChildrenOutsideABlockAreNot)
{
    SyntaxStatement child;
    child.keyword = "map";
    child.arguments = {SyntaxArgument{"Hips", false, 0}, SyntaxArgument{"Humanoid Root", true, 0}};
    SyntaxStatement withBlock;
    withBlock.keyword = "jointmap";
    withBlock.hasBlock = true;
    withBlock.children = {child};
    SyntaxStatement empty = withBlock;
    empty.children.clear();
    SyntaxStatement withoutBlock = withBlock; // children the syntax cannot hold without a block
    withoutBlock.hasBlock = false;
    std::ostringstream out;
    {
        SyntaxWriter w(out);
        w.write({withBlock, empty, withoutBlock});
    }
    EXPECT_EQ(out.str(), "jointmap {\n    map Hips \"Humanoid Root\"\n}\njointmap {\n}\njointmap\n");
}
