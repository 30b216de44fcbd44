#include "MocapTestUtil"

#include <osgActor/io/ClipSection>
#include <osgActor/mocap/BvhReader>

#include <gtest/gtest.h>

#include <glm/ext/scalar_constants.hpp>

#include <cmath>
#include <sstream>

using namespace osgActor;
using namespace osgActor::test;

namespace {

SyntaxStatement parseSection(const std::string& text)
{
    std::istringstream in(text);
    std::vector<SyntaxStatement> statements;
    std::string error;
    EXPECT_TRUE(parseSyntax(in, "clip.actor", statements, error)) << error;
    return statements.empty() ? SyntaxStatement() : statements.front();
}

void expectError(const std::string& text, const std::string& fileLine, const std::string& what)
{
    const ClipBuildResult result = clipFromSection(parseSection(text), "clip.actor");
    EXPECT_FALSE(result);
    EXPECT_EQ(result.error.rfind(fileLine, 0), 0u) << result.error;
    EXPECT_NE(result.error.find(what), std::string::npos) << result.error;
}

} // namespace

TEST(ClipSection, RefusesBrokenSections)
{
    expectError("clip a {\n interpolation smooth\n}\n", "clip.actor:2: ", "step, linear or cubic");
    expectError("clip a {\n rate 30\n channels x.rx x.ry\n frame 1\n}\n", "clip.actor:4: ", "1 values for 2 channels");
    expectError("clip a {\n rate 30\n channels x.rx\n frame nan\n}\n", "clip.actor:4: ", "'nan' is not a finite number");
    expectError("clip a {\n key 0 x.rx\n}\n", "clip.actor:2: ", "key time");
    expectError("clip a {\n wiggle 3\n}\n", "clip.actor:2: ", "unknown clip statement 'wiggle'");
    expectError("clip a {\n rate 0\n channels x.rx\n frame 1\n}\n", "clip.actor:1: ", "frame rate must be positive");
}

TEST(ClipSection, ReadsKeysInDegrees)
{
    const ClipBuildResult result =
        clipFromSection(parseSection("clip wave {\n interpolation cubic\n key 0 \"r_shoulder.rz\" 0\n"
                                     " key 1 \"r_shoulder.rz\" 90\n key 0 r_hand.tx 0.5\n}\n"),
                        "clip.actor");
    ASSERT_TRUE(result) << result.error;
    EXPECT_EQ(result.clip->getName(), "wave");
    ASSERT_EQ(result.clip->getNumChannels(), 2u);
    EXPECT_EQ(result.clip->getChannel(0).interpolation, Interpolation::Cubic);
    EXPECT_DOUBLE_EQ(result.clip->getKeyValue(0, 1), glm::pi<double>() / 2);
    EXPECT_DOUBLE_EQ(result.clip->getKeyValue(1, 0), 0.5);
}

TEST(ClipSection, RoundTripsMotionCapture)
{
    const MocapImport imported = readBvhFile(sharedMocap("bvh/12_03.bvh"));
    ASSERT_TRUE(imported) << imported.error;
    std::ostringstream out;
    writeSyntax(out, {clipToSection(*imported.clip)});
    const ClipBuildResult back = clipFromSection(parseSection(out.str()), "clip.actor");
    ASSERT_TRUE(back) << back.error;
    const Clip& a = *imported.clip;
    const Clip& b = *back.clip;
    ASSERT_EQ(b.getNumFrames(), a.getNumFrames());
    ASSERT_EQ(b.getNumChannels(), a.getNumChannels());
    EXPECT_NEAR(b.getFrameRate(), a.getFrameRate(), 1e-9 * a.getFrameRate());
    for (unsigned f = 0; f < a.getNumFrames(); f += 37)
        for (unsigned c = 0; c < a.getNumChannels(); ++c)
        {
            EXPECT_EQ(b.getChannel(c).target, a.getChannel(c).target);
            // 12 significant digits in the file.
            EXPECT_NEAR(b.getFrame(f)[c], a.getFrame(f)[c], 1e-10 * (1.0 + std::abs(a.getFrame(f)[c])));
        }
}
