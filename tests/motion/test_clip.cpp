#include <osgActor/core/ClipBuilder>

#include <gtest/gtest.h>

#include <glm/ext/scalar_constants.hpp>

#include <cmath>
#include <limits>

using namespace osgActor;

namespace {

const double kPi = glm::pi<double>();
const double kNaN = std::numeric_limits<double>::quiet_NaN();

ClipPtr threeKeys(Interpolation interpolation, const std::string& target = "knee.tx")
{
    ClipBuilder b("bump");
    const unsigned c = b.addChannel(target, interpolation);
    b.addKey(c, 0.0, 0.0);
    b.addKey(c, 1.0, 10.0);
    b.addKey(c, 2.0, 0.0);
    const ClipBuildResult result = b.build();
    EXPECT_TRUE(result) << result.error;
    return result.clip;
}

double sampleOne(const Clip& clip, double time)
{
    ClipCursor cursor;
    clip.initCursor(cursor);
    double value = 0.0;
    clip.sample(time, cursor, &value);
    return value;
}

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

TEST(Clip, InterpolatesStepLinearAndCubicKeys)
{
    const ClipPtr step = threeKeys(Interpolation::Step);
    EXPECT_DOUBLE_EQ(step->getDuration(), 2.0);
    EXPECT_DOUBLE_EQ(sampleOne(*step, 0.99), 0.0);
    EXPECT_DOUBLE_EQ(sampleOne(*step, 1.5), 10.0);

    const ClipPtr linear = threeKeys(Interpolation::Linear);
    EXPECT_DOUBLE_EQ(sampleOne(*linear, 0.5), 5.0);
    EXPECT_DOUBLE_EQ(sampleOne(*linear, 1.25), 7.5);
    EXPECT_DOUBLE_EQ(sampleOne(*linear, -3.0), 0.0) << "clamped to the first key";
    EXPECT_DOUBLE_EQ(sampleOne(*linear, 9.0), 0.0) << "clamped to the last key";

    // Catmull-Rom through (0, 0, 10, 0) at t = 0.5 (the first key repeated before the start):
    // 0.5 * (2*0 + 10*0.5 + (0 - 0 + 40 - 0)*0.25 + (0 - 0 - 30 + 0)*0.125) = 5.625.
    const ClipPtr cubic = threeKeys(Interpolation::Cubic);
    EXPECT_NEAR(sampleOne(*cubic, 0.5), 5.625, 1e-12);
    EXPECT_DOUBLE_EQ(sampleOne(*cubic, 1.0), 10.0) << "passes through its keys";
}

TEST(Clip, RotationsTakeTheShortWayRoundTheSeam)
{
    for (Interpolation interpolation : {Interpolation::Linear, Interpolation::Cubic})
    {
        ClipBuilder b("seam");
        const unsigned c = b.addChannel("neck.rz", interpolation);
        b.addKey(c, 0.0, 170.0 * kPi / 180.0);
        b.addKey(c, 1.0, -170.0 * kPi / 180.0);
        const ClipPtr clip = b.build().clip;
        ASSERT_TRUE(clip->getChannel(0).angular);
        // Halfway is 180 degrees (not 0, the long way round), and every sample stays within the 20 degrees
        // between the keys.
        EXPECT_NEAR(std::cos(sampleOne(*clip, 0.5)), -1.0, 1e-12);
        for (double t = 0.0; t <= 1.0; t += 0.125)
        {
            EXPECT_LE(std::abs(std::remainder(sampleOne(*clip, t) - kPi, 2 * kPi)), 10.0 * kPi / 180.0 + 1e-12) << t;
        }
        if (interpolation == Interpolation::Linear)
        {
            EXPECT_NEAR(std::remainder(sampleOne(*clip, 0.25) - 175.0 * kPi / 180.0, 2 * kPi), 0.0, 1e-12);
        }
    }
    // A translation has no seam.
    ClipBuilder b("slide");
    const unsigned c = b.addChannel("neck.tx");
    b.addKey(c, 0.0, 3.0);
    b.addKey(c, 1.0, -3.0);
    EXPECT_DOUBLE_EQ(sampleOne(*b.build().clip, 0.5), 0.0);
}

TEST(Clip, SamplesUniformFramesExactlyAndBetweenThem)
{
    ClipBuilder b("mocap");
    b.addChannel("hips.tx");
    b.addChannel("hips.rz");
    b.setFrames(120.0, {0.0, 0.0, 1.0, 0.5, 4.0, 1.0});
    const ClipPtr clip = b.build().clip;
    ASSERT_TRUE(clip);
    EXPECT_EQ(clip->getNumFrames(), 3u);
    EXPECT_DOUBLE_EQ(clip->getDuration(), 2.0 / 120.0);
    ClipCursor cursor;
    clip->initCursor(cursor);
    double values[2];
    clip->sample(1.0 / 120.0, cursor, values); // a frame time computed as frame / rate
    EXPECT_DOUBLE_EQ(values[0], 1.0);
    EXPECT_DOUBLE_EQ(values[1], 0.5);
    clip->sample(1.5 / 120.0, cursor, values);
    EXPECT_DOUBLE_EQ(values[0], 2.5);
    EXPECT_DOUBLE_EQ(values[1], 0.75);
    clip->sample(1.0, cursor, values);
    EXPECT_DOUBLE_EQ(values[0], 4.0) << "clamped to the last frame";
}

TEST(Clip, CursorsFollowTimeBackwardsAndForwards)
{
    const ClipPtr linear = threeKeys(Interpolation::Linear);
    ClipCursor cursor;
    linear->initCursor(cursor);
    double value = 0.0;
    for (double t : {1.9, 0.1, 1.5, 0.5, 2.0, 0.0})
    {
        linear->sample(t, cursor, &value);
        const double expected = t <= 1.0 ? 10.0 * t : 10.0 * (2.0 - t);
        EXPECT_NEAR(value, expected, 1e-12) << "t = " << t;
    }
}

TEST(Clip, SamplesARangeOfChannelsAsEachOnItsOwn)
{
    // Five channels of a uniform clip: a translation, two rotations (one wrapping through +-180 degrees between
    // frames 1 and 2), a stepped and a cubic one. A range of linear channels takes the vectorized path, the others
    // the per-channel one; all must agree with sampling every channel.
    ClipBuilder b("mixed");
    b.addChannel("hips.tx");
    b.addChannel("hips.rz");
    b.addChannel("neck.rz");
    b.addChannel("neck.rx", Interpolation::Step);
    b.addChannel("neck.ry", Interpolation::Cubic);
    const double d = kPi / 180.0;
    b.setFrames(10.0, {0.0, 10 * d, 100 * d, 1.0, 0.0,   //
                       1.0, 20 * d, 170 * d, 2.0, 1.0,    //
                       3.0, 40 * d, -170 * d, 3.0, 4.0,   //
                       6.0, 30 * d, -160 * d, 4.0, 9.0});
    const ClipPtr clip = b.build().clip;
    ASSERT_TRUE(clip);
    ClipCursor cursor;
    clip->initCursor(cursor);
    for (double time = 0.0; time <= 0.3; time += 0.0125)
    {
        double all[5], range[5];
        clip->sample(time, cursor, all);
        for (unsigned first = 0; first < 5; ++first)
            for (unsigned count = 1; first + count <= 5; ++count)
            {
                clip->sampleRange(time, cursor, first, count, range);
                for (unsigned i = 0; i < count; ++i)
                    EXPECT_EQ(range[i], all[first + i]) << "t " << time << ", channel " << first + i;
            }
    }
    // The wrap itself: halfway between 170 and -170 degrees is 180, the short way.
    double wrapped = 0.0;
    clip->sampleRange(0.15, cursor, 2, 1, &wrapped);
    EXPECT_NEAR(std::cos(wrapped), -1.0, 1e-12);
    double slide = 0.0;
    clip->sampleRange(0.15, cursor, 0, 1, &slide);
    EXPECT_DOUBLE_EQ(slide, 2.0);
}
