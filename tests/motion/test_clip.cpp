#include <osgActor/core/ClipBuilder>

#include <gtest/gtest.h>

#include <limits>

using namespace osgActor;

namespace {

const double kNaN = std::numeric_limits<double>::quiet_NaN();

std::string buildError(const ClipBuilder& builder) { return builder.build().error; }

} // namespace

TEST(ClipBuilder, RefusesBrokenClips)
{
    EXPECT_NE(buildError(ClipBuilder("empty")).find("clip 'empty' has no channel"), std::string::npos);

    ClipBuilder badTarget("c");
    badTarget.addChannel("knee");
    EXPECT_NE(buildError(badTarget).find("'knee' is not a DOF name"), std::string::npos);

    ClipBuilder twice("c");
    twice.addKey(twice.addChannel("knee.rx"), 0, 0);
    twice.addKey(twice.addChannel("knee.rx"), 0, 0);
    EXPECT_NE(buildError(twice).find("two channels for 'knee.rx'"), std::string::npos);

    ClipBuilder noKey("c");
    noKey.addChannel("knee.rx");
    EXPECT_NE(buildError(noKey).find("has no key"), std::string::npos);

    ClipBuilder backwards("c");
    const unsigned c = backwards.addChannel("knee.rx");
    backwards.addKey(c, 1.0, 0);
    backwards.addKey(c, 1.0, 0);
    EXPECT_NE(buildError(backwards).find("does not come after"), std::string::npos);

    ClipBuilder nanValue("c");
    nanValue.addKey(nanValue.addChannel("knee.rx"), 0.0, kNaN);
    EXPECT_NE(buildError(nanValue).find("non-finite value"), std::string::npos);

    ClipBuilder badRate("c");
    badRate.addChannel("knee.rx");
    badRate.setFrames(0.0, {1.0});
    EXPECT_NE(buildError(badRate).find("frame rate must be positive"), std::string::npos);

    ClipBuilder partial("c");
    partial.addChannel("knee.rx");
    partial.addChannel("knee.ry");
    partial.setFrames(30.0, {1.0, 2.0, 3.0});
    EXPECT_NE(buildError(partial).find("not a whole number of 2-channel frames"), std::string::npos);

    ClipBuilder nanFrame("c");
    nanFrame.addChannel("knee.rx");
    nanFrame.setFrames(30.0, {1.0, kNaN});
    EXPECT_NE(buildError(nanFrame).find("frame 1 channel 'knee.rx' is not a finite number"), std::string::npos);
}
