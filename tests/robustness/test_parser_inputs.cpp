/* The fuzzers' findings, kept: every file under tests/robustness/inputs/<parser>/ once crashed, hung, leaked or
 * broke the parser contract (fuzz/ParserContract). Each must now read, or fail with an error naming the file and
 * the line; the sanitizer build (scripts/test-sanitizers.sh) runs these too. */
#include "ParserContract"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>

using namespace osgActor;

namespace {

const std::string kInputs = std::string(OSGACTOR_TEST_SOURCE_DIR) + "/robustness/inputs/";

std::vector<std::filesystem::path> inputsOf(const std::string& parser)
{
    std::vector<std::filesystem::path> paths;
    for (const auto& entry : std::filesystem::directory_iterator(kInputs + parser))
        if (entry.is_regular_file() && entry.path().filename() != ".gitkeep") paths.push_back(entry.path());
    std::sort(paths.begin(), paths.end());
    return paths;
}

std::string bytesOf(const std::filesystem::path& path)
{
    std::ifstream in(path, std::ios::binary);
    std::ostringstream bytes;
    bytes << in.rdbuf();
    return bytes.str();
}

void expectContractKept(const std::string& parser, const std::function<std::string(const std::string&)>& check)
{
    for (const std::filesystem::path& path : inputsOf(parser))
        EXPECT_EQ(check(bytesOf(path)), "") << path;
}

} // namespace

TEST(ParserFindings, Actor)
{
    expectContractKept("actor", contract::checkActor);
}

TEST(ParserFindings, Bvh)
{
    expectContractKept("bvh", contract::checkBvh);
}

TEST(ParserFindings, Asf)
{
    expectContractKept("asf", contract::checkAsf);
}

TEST(ParserFindings, Amc)
{
    const std::string asf = std::string(OSGACTOR_TEST_MOCAP_DIR) + "/asfamc/11.asf";
    if (!std::filesystem::exists(asf)) GTEST_SKIP() << "no " << asf;
    const AsfImport skeleton = readAsfFile(asf);
    ASSERT_TRUE(skeleton) << skeleton.error;
    expectContractKept("amc", [&](const std::string& text) { return contract::checkAmc(text, skeleton); });
}

TEST(ParserFindings, TrajectoryCsv)
{
    expectContractKept("trajectory_csv", contract::checkTrajectoryCsv);
}

// A name (or any word) holding a control character, a NUL from a binary file, is refused by every reader, with the
// line it is on, before anything is read.
TEST(ParserContract, EveryReaderRefusesControlCharactersWithTheLine)
{
    const std::string nul(1, '\0');
    const std::string expected = ":2: a control character (0x00) in the text";
    std::istringstream actor("osgactor 1\nactor a" + nul + " {\n joint b\n}\n");
    EXPECT_EQ(readActor(actor, "t.actor").error.find("t.actor" + expected), 0u);
    std::istringstream bvh("HIERARCHY\nROOT hi" + nul + "ps\n{\n OFFSET 0 0 0\n}\nMOTION\nFrames: 0\nFrame Time: 1\n");
    EXPECT_EQ(readBvh(bvh, "t.bvh").error.find("t.bvh" + expected), 0u);
    std::istringstream asf(":root\n order TX" + nul + "\n:hierarchy\nbegin\nend\n");
    EXPECT_EQ(readAsf(asf, "t.asf").error.find("t.asf" + expected), 0u);
    const AsfImport skeleton = readAsfFile(std::string(OSGACTOR_TEST_MOCAP_DIR) + "/asfamc/11.asf");
    ASSERT_TRUE(skeleton) << skeleton.error;
    std::istringstream amc("1\nroot" + nul + " 0 0 0 0 0 0\n");
    EXPECT_EQ(readAmc(amc, "t.amc", skeleton).error.find("t.amc" + expected), 0u);
    std::istringstream csv("0,0,0,0,0\n1,0," + nul + "0,0,0\n");
    EXPECT_EQ(readTrajectoryCsv(csv, "t.csv").error.find("t.csv" + expected), 0u);
}

// A value the actor could not hold (a position or offset beyond +-1e150, kMaxDofMagnitude) is refused with the line
// it is on, not clamped or dropped later.
TEST(ParserContract, ValuesAnActorCannotHoldAreRefusedWithTheLine)
{
    std::istringstream actor("osgactor 1\nactor a {\n joint b\n trajectory t {\n  key 0 0 0 0 0\n"
                             "  key 1 2e150 0 0 0\n }\n}\n");
    EXPECT_EQ(readActor(actor, "t.actor").error,
              "t.actor:6: the key's position 2e150 lies beyond what an actor holds (+-1e+150)");
    std::istringstream csv("0,0,0,0,0\n1,0,-1e200,0,0\n");
    EXPECT_EQ(readTrajectoryCsv(csv, "t.csv").error, "t.csv:2: y -1e200 lies beyond what an actor holds (+-1e+150)");
    std::istringstream bvh("HIERARCHY\nROOT hips\n{\n OFFSET 0 0 0\n JOINT far\n {\n  OFFSET 1e300 0 0\n }\n}\n"
                           "MOTION\nFrames: 0\nFrame Time: 1\n");
    const std::string bvhError = readBvh(bvh, "t.bvh").error;
    EXPECT_EQ(bvhError.rfind("t.bvh:5: ", 0), 0u) << bvhError;
    EXPECT_NE(bvhError.find("offset beyond"), std::string::npos) << bvhError;
    std::istringstream asf(":root\n order TX TY TZ\n axis XYZ\n position 1e200 0 0\n:hierarchy\nbegin\nend\n");
    const std::string asfError = readAsf(asf, "t.asf").error;
    EXPECT_EQ(asfError.rfind("t.asf:1: ", 0), 0u) << asfError;
}

// The contract's round trips on the real files the fuzzers start from: read, write, read again, the same document.
TEST(ParserContract, EveryRealFileReadsWritesAndReadsBackTheSame)
{
    const std::string data = std::string(OSGACTOR_TEST_DATA_DIR) + "/";
    const std::string mocap = std::string(OSGACTOR_TEST_MOCAP_DIR) + "/";
    for (const char* actor : {"humanoid.actor", "insect.actor", "robot_arm.actor"})
        EXPECT_EQ(contract::checkActor(bytesOf(data + actor)), "") << actor;
    for (const char* bvh : {"bvh/12_03.bvh", "bvh/tpose.bvh"})
        EXPECT_EQ(contract::checkBvh(bytesOf(mocap + bvh)), "") << bvh;
    for (const char* asf : {"asfamc/11.asf", "asfamc/charleston.asf"})
        EXPECT_EQ(contract::checkAsf(bytesOf(mocap + asf)), "") << asf;
    const AsfImport skeleton = readAsfFile(mocap + "asfamc/11.asf");
    ASSERT_TRUE(skeleton) << skeleton.error;
    EXPECT_EQ(contract::checkAmc(bytesOf(mocap + "asfamc/11_01.amc"), skeleton), "");
    const std::string csv = std::string(OSGACTOR_TEST_SOURCE_DIR) + "/motion/data/cockroach.csv";
    EXPECT_EQ(contract::checkTrajectoryCsv(bytesOf(csv)), "");
}

// Found with the fuzz targets: BVH joints nest by recursion, and 100000 nested JOINTs overflowed the stack. Too big to
// keep
// as a file, so made here; the .actor syntax has the same bound.
TEST(ParserFindings, DeepNestingIsAnErrorNotAStackOverflow)
{
    const int depth = 100000;
    std::string bvh = "HIERARCHY\nROOT r\n{\nOFFSET 0 0 0\nCHANNELS 1 Xrotation\n";
    for (int j = 0; j < depth; ++j) bvh += "JOINT j\n{\nOFFSET 0 0 0\nCHANNELS 1 Xrotation\n";
    for (int j = 0; j <= depth; ++j) bvh += "}\n";
    bvh += "MOTION\nFrames: 1\nFrame Time: 0.1\n0\n";
    std::istringstream bvhIn(bvh);
    const MocapImport bvhResult = readBvh(bvhIn, "deep.bvh");
    EXPECT_FALSE(bvhResult);
    EXPECT_EQ(bvhResult.error.rfind("deep.bvh:806: ", 0), 0u) << bvhResult.error;
    EXPECT_NE(bvhResult.error.find("nested more than 200 deep"), std::string::npos) << bvhResult.error;

    std::string actor = "osgactor 1\nactor a {\n";
    for (int j = 0; j < depth; ++j) actor += "joint j" + std::to_string(j) + " {\n";
    EXPECT_EQ(contract::checkActor(actor), "");
}
