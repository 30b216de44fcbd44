/* Skeletons deeper than the .actor syntax nests (200 blocks): a chain of joints linked by 'parent' statements reads,
 * writes (in runs nested kMaxWrittenJointNesting deep, each run's first joint at the actor's level with 'parent'),
 * and reads back the same, without recursing once per joint. */
#include <osgActor/core/ActorDefinitionBuilder>
#include <osgActor/io/ActorReader>
#include <osgActor/io/ActorWriter>

#include <gtest/gtest.h>

#include <algorithm>
#include <sstream>
#include <string>

using namespace osgActor;

namespace {

/** "joint j0", then "joint jK { parent j(K-1) }": one chain, written flat. */
std::string flatChain(int length)
{
    std::string text = "osgactor 1\nactor chain {\n joint j0\n";
    for (int j = 1; j < length; ++j)
        text += " joint j" + std::to_string(j) + " { parent j" + std::to_string(j - 1) + " }\n";
    return text + "}\n";
}

ActorReadResult readText(const std::string& text)
{
    std::istringstream in(text);
    return readActor(in, "chain.actor");
}

} // namespace

TEST(DeepSkeletons, AChainAsDeepAsAllowedWritesAndReadsBack)
{
    const ActorReadResult first = readText(flatChain(static_cast<int>(kMaxJointDepth)));
    ASSERT_TRUE(first) << first.error;
    std::ostringstream written;
    writeActor(written, first.document);
    const ActorReadResult second = readText(written.str());
    ASSERT_TRUE(second) << second.error;
    ASSERT_EQ(second.definition->getNumJoints(), first.definition->getNumJoints());
    for (unsigned j = 0; j < first.definition->getNumJoints(); ++j)
    {
        ASSERT_EQ(second.definition->getJointName(j), first.definition->getJointName(j));
        ASSERT_EQ(second.definition->getParent(j), first.definition->getParent(j)) << j;
    }
    std::ostringstream again;
    writeActor(again, second.document);
    EXPECT_EQ(again.str(), written.str());
}

TEST(DeepSkeletons, AChainIsWrittenInRunsNestedAtMostTheWritersDepth)
{
    const ActorReadResult read = readText(flatChain(static_cast<int>(kMaxJointDepth)));
    ASSERT_TRUE(read) << read.error;
    std::ostringstream written;
    writeActor(written, read.document);
    // 1000 joints in runs of 32: every run but the first starts at the actor's level with 'parent'.
    ASSERT_EQ(kMaxWrittenJointNesting, 32u);
    std::size_t parents = 0, deepestIndent = 0;
    std::istringstream lines(written.str());
    for (std::string line; std::getline(lines, line);)
    {
        const std::size_t indent = line.find_first_not_of(' ');
        if (indent == std::string::npos) continue;
        deepestIndent = std::max(deepestIndent, indent);
        if (line.compare(indent, 7, "parent ") == 0) ++parents;
    }
    EXPECT_EQ(parents, 31u); // ceil(1000 / 32) - 1
    // Each run's first joint in the actor's block (one level), its 31 descendants nested below it (the joints hold
    // no statements): the deepest line 32 levels in, four spaces each.
    EXPECT_EQ(deepestIndent, 4u * 32);
}
