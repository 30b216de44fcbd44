/* The reader on damaged files: every prefix of a real file and seeded random corruptions either read or give an
 * error with a file:line message; never a crash, never a half-built result. And it is re-entrant. */
#include <osgActor/io/ActorReader>
#include <osgActor/io/ActorWriter>

#include <gtest/gtest.h>

#include <fstream>
#include <random>
#include <sstream>
#include <thread>

using namespace osgActor;

namespace {

std::string dataText(const std::string& name)
{
    std::ifstream in(std::string(OSGACTOR_TEST_DATA_DIR) + "/" + name);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

/** Reads text and checks the result is whole or empty with a located message. */
void expectWholeOrLocatedError(const std::string& text, const std::string& what)
{
    std::istringstream in(text);
    const ActorReadResult result = readActor(in, "d.actor");
    if (result)
    {
        EXPECT_TRUE(result.error.empty()) << what;
        EXPECT_EQ(result.definition->getNumJoints(), result.document.joints.size()) << what;
        return;
    }
    EXPECT_EQ(result.definition, nullptr) << what;
    EXPECT_TRUE(result.document.joints.empty()) << what;
    EXPECT_EQ(result.error.rfind("d.actor:", 0), 0u) << what << ": " << result.error;
    const std::string::size_type colon = result.error.find(':', 8);
    ASSERT_NE(colon, std::string::npos) << result.error;
    const int line = std::stoi(result.error.substr(8, colon - 8));
    EXPECT_GE(line, 1) << what << ": " << result.error;
}

} // namespace

TEST(ActorReaderRobustness, EveryPrefixOfARealFileReadsOrFailsWithALine)
{
    const std::string text = dataText("robot_arm.actor");
    ASSERT_GT(text.size(), 1000u);
    unsigned failures = 0;
    for (std::size_t length = 0; length < text.size(); ++length)
    {
        std::istringstream in(text.substr(0, length));
        if (!readActor(in, "d.actor")) ++failures;
        expectWholeOrLocatedError(text.substr(0, length), "prefix of " + std::to_string(length) + " bytes");
    }
    EXPECT_GT(failures, text.size() * 9 / 10) << "almost every truncation leaves a block open";
}

TEST(ActorReaderRobustness, RandomCorruptionsNeverCrash)
{
    const std::string text = dataText("humanoid.actor");
    std::mt19937 random(20020101u); // fixed: the same corruptions every run
    const char replacements[] = {'{', '}', '"', ';', '#', '\n', '\0', 'x', '-', '.', '9', ' ', '\\', '\xff'};
    for (int trial = 0; trial < 300; ++trial)
    {
        std::string damaged = text;
        const int edits = 1 + static_cast<int>(random() % 4);
        for (int e = 0; e < edits; ++e)
        {
            const std::size_t at = random() % damaged.size();
            switch (random() % 3)
            {
            case 0: damaged[at] = replacements[random() % sizeof(replacements)]; break;
            case 1: damaged.erase(at, 1 + random() % 20); break;
            default: damaged.insert(at, 1, replacements[random() % sizeof(replacements)]); break;
            }
        }
        expectWholeOrLocatedError(damaged, "trial " + std::to_string(trial));
    }
}

TEST(ActorReaderRobustness, ReadersInSeveralThreadsDoNotShareState)
{
    const std::string good = dataText("insect.actor");
    const std::string bad = "osgactor 1\nactor a {\n joint b {\n  dof rq\n }\n}\n";
    std::string expectedText;
    {
        std::istringstream in(good);
        std::ostringstream out;
        writeActor(out, readActor(in, "good").document);
        expectedText = out.str();
    }
    std::vector<std::string> texts(8), errors(8);
    std::vector<std::thread> threads;
    for (unsigned t = 0; t < 8; ++t)
    {
        threads.emplace_back([&, t] {
            for (int round = 0; round < 20; ++round)
            {
                std::istringstream goodIn(good);
                std::ostringstream out;
                writeActor(out, readActor(goodIn, "good").document);
                texts[t] = out.str();
                std::istringstream badIn(bad);
                errors[t] = readActor(badIn, "bad" + std::to_string(t)).error;
            }
        });
    }
    for (std::thread& thread : threads) thread.join();
    for (unsigned t = 0; t < 8; ++t)
    {
        EXPECT_EQ(texts[t], expectedText);
        EXPECT_EQ(errors[t], "bad" + std::to_string(t) + ":4: 'rq' is not a DOF (rx, ry, rz, tx, ty, tz)");
    }
}
