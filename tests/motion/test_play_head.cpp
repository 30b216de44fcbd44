// PlayHead, the play head clip and trajectory players share: refusals first, then the folds of each play mode worked
// out by hand, and how it advances.
#include <osgActor/core/PlayHead>

#include <gtest/gtest.h>

#include <limits>

using namespace osgActor;

namespace {

const double kNaN = std::numeric_limits<double>::quiet_NaN();
const double kInfinity = std::numeric_limits<double>::infinity();

PlayHead headIn(PlayMode mode)
{
    PlayHead head;
    head.setMode(mode);
    return head;
}

} // namespace

TEST(PlayHead, RefusesANonFiniteSpeedOrTime)
{
    PlayHead head;
    ASSERT_TRUE(head.setSpeed(-2.0));
    ASSERT_TRUE(head.seek(3.0));
    EXPECT_FALSE(head.setSpeed(kNaN));
    EXPECT_FALSE(head.setSpeed(kInfinity));
    EXPECT_FALSE(head.seek(kNaN));
    EXPECT_FALSE(head.seek(-kInfinity));
    EXPECT_EQ(head.getSpeed(), -2.0) << "the old speed kept";
    EXPECT_EQ(head.getTime(), 3.0) << "the old time kept";
}

TEST(PlayHead, StartsPlayingAtTimeZeroAtSpeedOneAndLoops)
{
    const PlayHead head;
    EXPECT_TRUE(head.isPlaying());
    EXPECT_EQ(head.getTime(), 0.0);
    EXPECT_EQ(head.getSpeed(), 1.0);
    EXPECT_EQ(head.getMode(), PlayMode::Loop);
}

TEST(PlayHead, AdvancesByTheFrameTimeTimesTheSpeedOnlyWhilePlaying)
{
    PlayHead head;
    head.setSpeed(-0.5);
    head.advance(2.0);
    EXPECT_EQ(head.getTime(), -1.0);
    head.pause();
    head.advance(2.0);
    EXPECT_EQ(head.getTime(), -1.0) << "paused";
    head.play();
    head.advance(-4.0); // simulation time went back: a viewer scrubbing
    EXPECT_EQ(head.getTime(), 1.0);
}

TEST(PlayHead, OnceClampsToTheSpan)
{
    const PlayHead head = headIn(PlayMode::Once);
    // The span [10, 12]: a trajectory's keys from 10 s to 12 s.
    EXPECT_EQ(head.fold(9.0, 10.0, 2.0), 10.0);
    EXPECT_EQ(head.fold(11.5, 10.0, 2.0), 11.5);
    EXPECT_EQ(head.fold(30.0, 10.0, 2.0), 12.0);
}

TEST(PlayHead, LoopWrapsRoundFromEitherEnd)
{
    const PlayHead head = headIn(PlayMode::Loop);
    EXPECT_EQ(head.fold(0.5, 0.0, 2.0), 0.5);
    EXPECT_EQ(head.fold(5.0, 0.0, 2.0), 1.0) << "two and a half loops";
    EXPECT_EQ(head.fold(-0.5, 0.0, 2.0), 1.5) << "before the start: the end of the loop before";
    EXPECT_EQ(head.fold(13.0, 10.0, 2.0), 11.0) << "a span that does not start at 0";
}

TEST(PlayHead, PingPongTurnsRoundAtEachEnd)
{
    const PlayHead head = headIn(PlayMode::PingPong);
    EXPECT_EQ(head.fold(1.5, 0.0, 2.0), 1.5) << "out";
    EXPECT_EQ(head.fold(3.0, 0.0, 2.0), 1.0) << "on the way back";
    EXPECT_EQ(head.fold(4.5, 0.0, 2.0), 0.5) << "out again";
    EXPECT_EQ(head.fold(-0.5, 0.0, 2.0), 0.5) << "before the start, reflected";
}

TEST(PlayHead, ASpanWithoutLengthHoldsItsStart)
{
    for (PlayMode mode : {PlayMode::Once, PlayMode::Loop, PlayMode::PingPong})
    {
        EXPECT_EQ(headIn(mode).fold(7.0, 3.0, 0.0), 3.0);
        EXPECT_EQ(headIn(mode).fold(7.0, 3.0, kNaN), 3.0);
    }
}

TEST(PlayHead, IsFinishedOnlyOnceItLeftTheSpanInTheDirectionItPlays)
{
    PlayHead head = headIn(PlayMode::Once);
    head.seek(1.9);
    EXPECT_FALSE(head.isFinished(0.0, 2.0));
    head.seek(2.0);
    EXPECT_TRUE(head.isFinished(0.0, 2.0));
    head.setSpeed(-1.0);
    EXPECT_FALSE(head.isFinished(0.0, 2.0)) << "playing backwards, it has the whole span before it";
    head.seek(0.0);
    EXPECT_TRUE(head.isFinished(0.0, 2.0));
    head.setMode(PlayMode::Loop);
    EXPECT_FALSE(head.isFinished(0.0, 2.0)) << "a loop never finishes";
}

TEST(PlayMode, NamesAreTheActorFormatsWordsBothWays)
{
    for (PlayMode mode : {PlayMode::Once, PlayMode::Loop, PlayMode::PingPong})
    {
        PlayMode parsed = PlayMode::Once;
        ASSERT_TRUE(parsePlayMode(playModeName(mode), parsed)) << playModeName(mode);
        EXPECT_EQ(parsed, mode);
    }
    EXPECT_STREQ(playModeName(PlayMode::PingPong), "pingpong");
    PlayMode untouched = PlayMode::PingPong;
    EXPECT_FALSE(parsePlayMode("Loop", untouched)) << "words are lower case";
    EXPECT_EQ(untouched, PlayMode::PingPong);
}
