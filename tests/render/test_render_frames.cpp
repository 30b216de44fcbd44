// osgActor::Offscreen's sequence API, as users' own tests call it: any OSG scene (none of these is an actor),
// rendered at given times, the same bytes on every run and in every part; and the determinism check.
#include <osgActor/Offscreen/ImageComparison>
#include <osgActor/Offscreen/OffscreenRenderer>
#include <osgActor/Offscreen/RenderFrames>

#include <osgDB/ReadFile>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

using namespace osgActor;

namespace {

const std::string kScenes = std::string(OSGACTOR_TEST_SOURCE_DIR) + "/render/scenes/";

/** Small frames, 8 per second, from a fixed camera above the front of the floor. */
RenderSettings smallFrames()
{
    RenderSettings settings;
    settings.width = 160;
    settings.height = 120;
    settings.fps = 8.0;
    settings.hasEye = true;
    settings.eye = osg::Vec3d(0.0, -7.0, 4.0);
    settings.hasCenter = true;
    settings.center = osg::Vec3d(0.0, 0.0, 0.8);
    return settings;
}

std::vector<double> frameTimes(unsigned first, unsigned last, double fps)
{
    std::vector<double> times;
    for (unsigned frame = first; frame <= last; ++frame) times.push_back(frame / fps);
    return times;
}

bool sameBytes(const osg::Image& a, const osg::Image& b)
{
    const ImageComparison comparison = compareImages(a, b, 0);
    return comparison.comparable && comparison.maxChannelDifference == 0;
}

std::vector<osg::ref_ptr<osg::Image>> renderSceneFile(const std::string& name, const std::vector<double>& times,
                                                      const RenderSettings& settings)
{
    std::vector<osg::ref_ptr<osg::Image>> images;
    std::string error;
    EXPECT_TRUE(renderFile(kScenes + name, times, settings, images, error)) << error;
    EXPECT_EQ(images.size(), times.size());
    return images;
}

} // namespace

TEST(RenderFrames, RefusesWhatItCannotRender)
{
    const osg::ref_ptr<osg::Node> scene = osgDB::readRefNodeFile(kScenes + "box.osgt");
    ASSERT_TRUE(scene.valid());
    std::vector<osg::ref_ptr<osg::Image>> images;
    std::string error;
    EXPECT_FALSE(renderFrames(nullptr, {0.0}, smallFrames(), images, error));
    EXPECT_NE(error.find("no scene"), std::string::npos) << error;
    error.clear();
    EXPECT_FALSE(renderFrames(scene.get(), {}, smallFrames(), images, error));
    EXPECT_NE(error.find("no time"), std::string::npos) << error;
    error.clear();
    EXPECT_FALSE(renderFrames(scene.get(), {0.5, 0.25}, smallFrames(), images, error));
    EXPECT_NE(error.find("must not go back"), std::string::npos) << error;
    error.clear();
    EXPECT_FALSE(renderFrames(scene.get(), {std::numeric_limits<double>::quiet_NaN()}, smallFrames(), images, error));
    EXPECT_NE(error.find("not a finite time"), std::string::npos) << error;
    error.clear();
    EXPECT_FALSE(renderFrames(scene.get(), {-1.0}, smallFrames(), images, error));
    error.clear();
    EXPECT_FALSE(renderFrames(scene.get(), {1e9}, smallFrames(), images, error));
    EXPECT_NE(error.find("too many"), std::string::npos) << error;

    RenderSettings settings = smallFrames();
    settings.framingTime = 1.0;
    error.clear();
    EXPECT_FALSE(renderFrames(scene.get(), {0.5}, settings, images, error));
    EXPECT_NE(error.find("framing time"), std::string::npos) << error;
    settings = smallFrames();
    settings.width = 0;
    EXPECT_FALSE(settings.validate(error));
    EXPECT_FALSE(renderFrames(scene.get(), {0.0}, settings, images, error));
    settings = smallFrames();
    settings.fps = 0.0;
    EXPECT_FALSE(settings.validate(error));
    settings = smallFrames();
    settings.eye = settings.center;
    EXPECT_FALSE(settings.validate(error));
    EXPECT_TRUE(images.empty());
}

TEST(RenderFrames, ReadingAMissingFileNamesIt)
{
    std::vector<osg::ref_ptr<osg::Image>> images;
    std::string error;
    EXPECT_FALSE(renderFile(kScenes + "missing.osgt", {0.0}, smallFrames(), images, error));
    EXPECT_NE(error.find("missing.osgt"), std::string::npos) << error;
    EXPECT_TRUE(images.empty());
}

TEST(RenderFrames, AnAnimationPathSceneIsTheSameBytesOnEveryRun)
{
    const std::vector<double> times = frameTimes(0, 7, 8.0);
    const auto first = renderSceneFile("animation_path.osgt", times, smallFrames());
    const auto second = renderSceneFile("animation_path.osgt", times, smallFrames());
    ASSERT_EQ(first.size(), 8u);
    ASSERT_EQ(second.size(), 8u);
    for (size_t i = 0; i < first.size(); ++i) EXPECT_TRUE(sameBytes(*first[i], *second[i])) << "frame " << i;
    EXPECT_FALSE(sameBytes(*first.front(), *first.back())) << "the box moves along its path";
}

TEST(RenderFrames, APartFramedWhereTheSequenceStartsIsTheSameAsTheWholeRunsFrames)
{
    // Particles emit from the cull traversal, drawing std::rand(): a part that starts at frame 6 steps (and culls)
    // frames 0..5 and frames its camera (auto-framed here) at frame 0, as the whole run did.
    RenderSettings settings = smallFrames();
    settings.hasEye = false;
    settings.hasCenter = false;
    const auto whole = renderSceneFile("particles.osgt", frameTimes(0, 11, 8.0), settings);
    settings.framingTime = 0.0;
    const auto part = renderSceneFile("particles.osgt", frameTimes(6, 11, 8.0), settings);
    ASSERT_EQ(whole.size(), 12u);
    ASSERT_EQ(part.size(), 6u);
    for (size_t i = 0; i < part.size(); ++i) EXPECT_TRUE(sameBytes(*part[i], *whole[6 + i])) << "frame " << 6 + i;
    EXPECT_FALSE(sameBytes(*whole[6], *whole[11])) << "the particles move";
}

TEST(RenderFrames, ParticlesFollowTheSeed)
{
    const std::vector<double> times = frameTimes(8, 8, 8.0);
    RenderSettings settings = smallFrames();
    const auto seedOne = renderSceneFile("particles.osgt", times, settings);
    const auto seedOneAgain = renderSceneFile("particles.osgt", times, settings);
    settings.seed = 2;
    const auto seedTwo = renderSceneFile("particles.osgt", times, settings);
    ASSERT_EQ(seedTwo.size(), 1u);
    EXPECT_TRUE(sameBytes(*seedOne[0], *seedOneAgain[0]));
    EXPECT_FALSE(sameBytes(*seedOne[0], *seedTwo[0])) << "another seed, other particles";
}

TEST(RenderFrames, OsgAnimationPlaysWhenAsked)
{
    const osg::ref_ptr<osg::Node> stored = osgDB::readRefNodeFile(kScenes + "osganimation.osgt");
    ASSERT_TRUE(stored.valid());
    EXPECT_EQ(playOsgAnimations(*stored), 1u) << "the scene's one animation";
    EXPECT_EQ(playOsgAnimations(*stored), 0u) << "it plays already";

    const std::vector<double> times = {0.0, 0.5};
    RenderSettings settings = smallFrames();
    const auto still = renderSceneFile("osganimation.osgt", times, settings);
    settings.playAnimations = true;
    const auto played = renderSceneFile("osganimation.osgt", times, settings);
    const auto playedAgain = renderSceneFile("osganimation.osgt", times, settings);
    ASSERT_EQ(played.size(), 2u);
    EXPECT_TRUE(sameBytes(*still[0], *still[1])) << "a file keeps its animations, not whether they play";
    EXPECT_FALSE(sameBytes(*played[0], *played[1])) << "the box moves from t = 0 to t = 0.5 s";
    EXPECT_TRUE(sameBytes(*played[1], *playedAgain[1]));
}

TEST(RenderFrames, DeterminismCheckPassesOnParticles)
{
    const DeterminismCheck check = checkDeterminism(
        [](std::string& error) { return readScene({kScenes + "particles.osgt"}, error); }, frameTimes(0, 9, 8.0),
        smallFrames());
    EXPECT_TRUE(check.completed) << check.error;
    EXPECT_EQ(check.firstDifferingFrame, -1);
}

TEST(RenderFrames, DeterminismCheckFindsACallbackReadingTheClock)
{
    // The test pseudo-loader hangs the scene below a transform that the wall clock moves.
    unsigned numFrames = 0;
    const DeterminismCheck check = checkDeterminism(
        [](std::string& error) { return readScene({kScenes + "box.osgt.osgactortestclock"}, error); },
        frameTimes(0, 5, 8.0), smallFrames(), [&numFrames] { ++numFrames; });
    EXPECT_TRUE(check.completed) << check.error;
    EXPECT_GE(check.firstDifferingFrame, 0);
    EXPECT_EQ(numFrames, 6u + unsigned(check.firstDifferingFrame) + 1u) << "the first run, then up to the difference";
}

TEST(RenderFrames, DeterminismCheckSaysWhyASceneCannotBeMade)
{
    const DeterminismCheck check = checkDeterminism(
        [](std::string& error) { return readScene({kScenes + "missing.osgt"}, error); }, {0.0}, smallFrames());
    EXPECT_FALSE(check.completed);
    EXPECT_NE(check.error.find("missing.osgt"), std::string::npos) << check.error;
}
