// SamplingJob: the values of a clip's channels at a time, checked against values worked out by hand. Invalid jobs
// first.
#include <osgActor/core/ClipBuilder>
#include <osgActor/core/SamplingJob>

#include <gtest/gtest.h>

#include <glm/ext/scalar_constants.hpp>

#include <cmath>
#include <cstdint>
#include <limits>

using namespace osgActor;

namespace {

const double kPi = glm::pi<double>();

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

/** A uniform clip of two channels and three frames at 30 per second. */
ClipPtr twoChannelFrames()
{
    ClipBuilder b("frames");
    b.addChannel("hips.tx");
    b.addChannel("hips.rz");
    b.setFrames(30.0, {0.0, 0.0, 1.0, 0.5, 4.0, 1.0});
    return b.build().clip;
}

/** Every channel of clip at time into values (count of them). */
void sampleAll(const Clip& clip, double time, ClipCursor& cursor, double* values, unsigned count)
{
    ASSERT_TRUE(sampleEveryChannel(clip, time, cursor, {values, count}));
}

/** Channels first .. first + count - 1 of clip at time into values, through the job. */
void sampleRange(const Clip& clip, double time, ClipCursor& cursor, unsigned first, unsigned count, double* values)
{
    SamplingJob job;
    job.clip = &clip;
    job.time = time;
    job.cursor = &cursor;
    job.firstChannel = first;
    job.values = {values, count};
    ASSERT_TRUE(job.run());
}

double sampleOne(const Clip& clip, double time)
{
    ClipCursor cursor;
    clip.initCursor(cursor);
    double value = 0.0;
    sampleAll(clip, time, cursor, &value, 1);
    return value;
}

} // namespace

// --- invalid jobs are refused and touch nothing ---

TEST(SamplingJob, RefusesAJobWithoutClipOrCursor)
{
    const ClipPtr clip = twoChannelFrames();
    ClipCursor cursor;
    clip->initCursor(cursor);
    double values[2] = {-1.0, -1.0};
    SamplingJob job;
    EXPECT_FALSE(job.validate()) << "nothing set";
    job.values = values;
    job.cursor = &cursor;
    EXPECT_FALSE(job.run()) << "no clip";
    job.clip = clip.get();
    job.cursor = nullptr;
    EXPECT_FALSE(job.run()) << "no cursor";
    EXPECT_EQ(values[0], -1.0) << "a refused run touches nothing";
    job.cursor = &cursor;
    EXPECT_TRUE(job.run());
    EXPECT_EQ(values[0], 0.0);
}

TEST(SamplingJob, RefusesACursorMadeForAnotherClip)
{
    const ClipPtr keyed = threeKeys(Interpolation::Linear);
    const ClipPtr uniform = twoChannelFrames();
    ClipCursor uninitialised, uniformCursor;
    uniform->initCursor(uniformCursor);
    double value = -1.0;
    SamplingJob job;
    job.clip = keyed.get();
    job.values = {&value, 1};
    job.cursor = &uninitialised;
    EXPECT_FALSE(job.validate()) << "a keyed clip needs a key per channel in its cursor";
    job.cursor = &uniformCursor;
    EXPECT_FALSE(job.validate()) << "a uniform clip's cursor is empty";
    ClipCursor keyedCursor;
    keyed->initCursor(keyedCursor);
    job.cursor = &keyedCursor;
    EXPECT_TRUE(job.run());
    EXPECT_EQ(value, 0.0);
    // A uniform clip reads no cursor: any will do.
    double values[2] = {-1.0, -1.0};
    job.clip = uniform.get();
    job.values = values;
    EXPECT_TRUE(job.run());
    EXPECT_EQ(values[1], 0.0);
}

TEST(SamplingJob, RefusesChannelsTheClipDoesNotHave)
{
    const ClipPtr clip = twoChannelFrames(); // channels 0 and 1
    ClipCursor cursor;
    clip->initCursor(cursor);
    double values[3] = {-1.0, -1.0, -1.0};
    SamplingJob job;
    job.clip = clip.get();
    job.cursor = &cursor;
    job.values = {values, 3};
    EXPECT_FALSE(job.validate()) << "a range of three channels in a clip of two";
    job.values = {values, 2};
    job.firstChannel = 1;
    EXPECT_FALSE(job.validate()) << "channels 1 and 2";
    job.firstChannel = 3;
    job.values = {values, 0};
    EXPECT_FALSE(job.validate()) << "an empty range starting past the end";
    job.firstChannel = 2;
    EXPECT_TRUE(job.validate()) << "an empty range at the end";

    const std::uint32_t listed[2] = {1, 2};
    job.channels = listed;
    job.values = {values, 2};
    EXPECT_FALSE(job.run()) << "listed channel 2";
    const std::uint32_t fine[2] = {1, 0};
    job.channels = fine;
    job.values = {values, 1};
    EXPECT_FALSE(job.run()) << "two channels listed, room for one value";
    EXPECT_EQ(values[0], -1.0) << "a refused run touches nothing";
    job.values = {values, 2};
    job.time = 1.0 / 30.0;
    EXPECT_TRUE(job.run());
    EXPECT_EQ(values[0], 0.5) << "channel 1 at frame 1";
    EXPECT_EQ(values[1], 1.0) << "channel 0 at frame 1";
}

TEST(SamplingJob, EveryChannelNeedsRoomForEveryChannel)
{
    const ClipPtr clip = twoChannelFrames();
    ClipCursor cursor;
    clip->initCursor(cursor);
    double values[3] = {-1.0, -1.0, -1.0};
    EXPECT_FALSE(sampleEveryChannel(*clip, 0.0, cursor, {values, 1}));
    EXPECT_FALSE(sampleEveryChannel(*clip, 0.0, cursor, {values, 3}));
    EXPECT_EQ(values[0], -1.0);
    EXPECT_TRUE(sampleEveryChannel(*clip, 2.0 / 30.0, cursor, {values, 2}));
    EXPECT_EQ(values[0], 4.0);
    EXPECT_EQ(values[1], 1.0);
}

TEST(SamplingJob, TimeOutsideTheClipIsClampedAndNaNOrInfinitySamplesTheStart)
{
    ClipBuilder b("ramp");
    const unsigned c = b.addChannel("knee.tx");
    b.addKey(c, 0.0, 0.0);
    b.addKey(c, 1.0, 10.0);
    const ClipPtr clip = b.build().clip;
    ASSERT_TRUE(clip);
    EXPECT_EQ(sampleOne(*clip, -5.0), 0.0) << "clamped to the first key";
    EXPECT_EQ(sampleOne(*clip, 1e300), 10.0) << "clamped to the last key";
    EXPECT_EQ(sampleOne(*clip, std::numeric_limits<double>::quiet_NaN()), 0.0);
    EXPECT_EQ(sampleOne(*clip, std::numeric_limits<double>::infinity()), 0.0);
}

// --- what it samples ---

TEST(SamplingJob, InterpolatesStepLinearAndCubicKeys)
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

TEST(SamplingJob, RotationsTakeTheShortWayRoundTheSeam)
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

TEST(SamplingJob, SamplesUniformFramesExactlyAndBetweenThem)
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
    sampleAll(*clip, 1.0 / 120.0, cursor, values, 2); // a frame time computed as frame / rate
    EXPECT_DOUBLE_EQ(values[0], 1.0);
    EXPECT_DOUBLE_EQ(values[1], 0.5);
    sampleAll(*clip, 1.5 / 120.0, cursor, values, 2);
    EXPECT_DOUBLE_EQ(values[0], 2.5);
    EXPECT_DOUBLE_EQ(values[1], 0.75);
    sampleAll(*clip, 1.0, cursor, values, 2);
    EXPECT_DOUBLE_EQ(values[0], 4.0) << "clamped to the last frame";
}

TEST(SamplingJob, CursorsFollowTimeBackwardsAndForwards)
{
    const ClipPtr linear = threeKeys(Interpolation::Linear);
    ClipCursor cursor;
    linear->initCursor(cursor);
    double value = 0.0;
    for (double t : {1.9, 0.1, 1.5, 0.5, 2.0, 0.0})
    {
        sampleAll(*linear, t, cursor, &value, 1);
        const double expected = t <= 1.0 ? 10.0 * t : 10.0 * (2.0 - t);
        EXPECT_NEAR(value, expected, 1e-12) << "t = " << t;
    }
}

TEST(SamplingJob, SamplesARangeOfChannelsAsEachOnItsOwn)
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
        sampleAll(*clip, time, cursor, all, 5);
        for (unsigned first = 0; first < 5; ++first)
            for (unsigned count = 1; first + count <= 5; ++count)
            {
                sampleRange(*clip, time, cursor, first, count, range);
                for (unsigned i = 0; i < count; ++i)
                    EXPECT_EQ(range[i], all[first + i]) << "t " << time << ", channel " << first + i;
            }
    }
    // The wrap itself: halfway between 170 and -170 degrees is 180, the short way.
    double wrapped = 0.0;
    sampleRange(*clip, 0.15, cursor, 2, 1, &wrapped);
    EXPECT_NEAR(std::cos(wrapped), -1.0, 1e-12);
    double slide = 0.0;
    sampleRange(*clip, 0.15, cursor, 0, 1, &slide);
    EXPECT_DOUBLE_EQ(slide, 2.0);
}
