// osgActor::Offscreen's image comparison, which users' render tests and osgactorrender --compare rely on: it must
// tell images apart, tolerate what it should, and give figures that can be derived by hand.
#include "ImageCompare.h"

#include <osgActor/Offscreen/ImageComparison>

#include <osgDB/FileUtils>
#include <osgDB/WriteFile>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <vector>

using namespace osgActor;
using namespace osgActor::test;

namespace {

osg::ref_ptr<osg::Image> solidImage(int width, int height, unsigned char r, unsigned char g, unsigned char b)
{
    osg::ref_ptr<osg::Image> image = new osg::Image;
    image->allocateImage(width, height, 1, GL_RGB, GL_UNSIGNED_BYTE);
    for (int i = 0; i < width * height; ++i)
    {
        image->data()[3 * i + 0] = r;
        image->data()[3 * i + 1] = g;
        image->data()[3 * i + 2] = b;
    }
    return image;
}

} // namespace

TEST(ImageComparison, RefusesImagesOfDifferentSizes)
{
    const ImageComparison comparison = compareImages(*solidImage(4, 4, 0, 0, 0), *solidImage(4, 5, 0, 0, 0), 0);
    EXPECT_FALSE(comparison.comparable);
    EXPECT_FALSE(comparison.matches(1.0)) << "no share of differing pixels makes different sizes match";
    EXPECT_NE(comparison.whyNotComparable.find("4x4"), std::string::npos) << comparison.whyNotComparable;
    EXPECT_NE(comparison.whyNotComparable.find("4x5"), std::string::npos) << comparison.whyNotComparable;
    EXPECT_FALSE(makeDiffImage(*solidImage(4, 4, 0, 0, 0), *solidImage(4, 5, 0, 0, 0), 0).valid());
}

TEST(ImageComparison, RefusesImagesThatAreNotRgb8)
{
    osg::ref_ptr<osg::Image> rgba = new osg::Image;
    rgba->allocateImage(4, 4, 1, GL_RGBA, GL_UNSIGNED_BYTE);
    EXPECT_FALSE(isRgb8(*rgba));
    const ImageComparison comparison = compareImages(*rgba, *solidImage(4, 4, 0, 0, 0), 0);
    EXPECT_FALSE(comparison.comparable);
    EXPECT_NE(comparison.whyNotComparable.find("not 8-bit RGB"), std::string::npos);
}

TEST(ImageComparison, ReadingAMissingFileNamesIt)
{
    std::string error;
    EXPECT_FALSE(readRgbImage("no/such/reference_0001.png", error).valid());
    EXPECT_NE(error.find("no/such/reference_0001.png"), std::string::npos) << error;
}

TEST(ImageComparison, MissingReferenceFailsAndSaysHowToMakeIt)
{
    const char* update = std::getenv("OSGACTOR_UPDATE_REFERENCES");
    if (update != nullptr && std::string(update) == "1") GTEST_SKIP() << "writing references";
    const ::testing::AssertionResult result = matchesReference(*solidImage(4, 4, 0, 0, 0), "no_such_reference");
    EXPECT_FALSE(result);
    EXPECT_NE(std::string(result.message()).find("OSGACTOR_UPDATE_REFERENCES"), std::string::npos);
}

TEST(ImageComparison, IdenticalImagesMatchWithAnInfinitePsnr)
{
    const ImageComparison comparison =
        compareImages(*solidImage(8, 6, 10, 20, 30), *solidImage(8, 6, 10, 20, 30), 0);
    ASSERT_TRUE(comparison.comparable);
    EXPECT_EQ(comparison.numPixels, 48u);
    EXPECT_EQ(comparison.numOverTolerance, 0u);
    EXPECT_EQ(comparison.maxChannelDifference, 0);
    EXPECT_TRUE(std::isinf(comparison.psnr));
    EXPECT_TRUE(comparison.matches());
}

TEST(ImageComparison, CountsPixelsOverTheToleranceOnly)
{
    osg::ref_ptr<osg::Image> rendered = solidImage(10, 10, 100, 100, 100);
    const osg::ref_ptr<osg::Image> reference = solidImage(10, 10, 100, 100, 100);
    rendered->data(1, 2)[0] = 110; // within a tolerance of 10
    rendered->data(3, 4)[2] = 111; // over it
    rendered->data(5, 6)[1] = 0;   // far over it
    const ImageComparison comparison = compareImages(*rendered, *reference, 10);
    ASSERT_TRUE(comparison.comparable);
    EXPECT_EQ(comparison.tolerance, 10);
    EXPECT_EQ(comparison.numOverTolerance, 2u);
    EXPECT_EQ(comparison.maxChannelDifference, 100);
    EXPECT_DOUBLE_EQ(comparison.getShareOverTolerance(), 0.02);
    EXPECT_FALSE(comparison.matches());
    EXPECT_FALSE(comparison.matches(0.019));
    EXPECT_TRUE(comparison.matches(0.02)) << "2 of 100 pixels is within an allowed share of 2 %";
}

TEST(ImageComparison, PsnrIsTheMeanSquareErrorOverEveryChannelInDecibels)
{
    // Every channel of every pixel 10 levels off: MSE = 100, PSNR = 10 log10(255^2 / 100) = 28.1308 dB.
    const ImageComparison uniform =
        compareImages(*solidImage(10, 10, 110, 110, 110), *solidImage(10, 10, 100, 100, 100), 2);
    EXPECT_NEAR(uniform.psnr, 10.0 * std::log10(65025.0 / 100.0), 1e-9);
    EXPECT_NEAR(uniform.psnr, 28.1308, 1e-4);
    EXPECT_EQ(uniform.numOverTolerance, 100u);

    // One channel of one pixel of 10 x 10 fully off: MSE = 255^2 / 300, PSNR = 10 log10(300) = 24.7712 dB.
    osg::ref_ptr<osg::Image> rendered = solidImage(10, 10, 0, 0, 0);
    rendered->data(9, 9)[1] = 255;
    const ImageComparison single = compareImages(*rendered, *solidImage(10, 10, 0, 0, 0), 2);
    EXPECT_NEAR(single.psnr, 24.7712, 1e-4);
    EXPECT_EQ(single.maxChannelDifference, 255);
}

TEST(ImageComparison, DiffImageShowsTheDifferencesOverADimmedReference)
{
    osg::ref_ptr<osg::Image> rendered = solidImage(6, 4, 90, 150, 210);
    const osg::ref_ptr<osg::Image> reference = solidImage(6, 4, 90, 150, 210);
    rendered->data(1, 1)[0] = 95;  // 5 over a tolerance of 2: red 128 + 8 * 3
    rendered->data(2, 1)[2] = 150; // 60 over: full red
    rendered->data(3, 2)[1] = 151; // 1, within the tolerance: blue 128 + 8
    const osg::ref_ptr<osg::Image> diff = makeDiffImage(*rendered, *reference, 2);
    ASSERT_TRUE(diff.valid());
    ASSERT_TRUE(isRgb8(*diff));
    const auto pixel = [&](int x, int y) {
        const unsigned char* p = diff->data(x, y);
        return std::vector<int>{p[0], p[1], p[2]};
    };
    EXPECT_EQ(pixel(1, 1), (std::vector<int>{152, 0, 0}));
    EXPECT_EQ(pixel(2, 1), (std::vector<int>{255, 0, 0}));
    EXPECT_EQ(pixel(3, 2), (std::vector<int>{30, 50, 136}));
    EXPECT_EQ(pixel(0, 0), (std::vector<int>{30, 50, 70})) << "elsewhere: the reference at a third of its brightness";
}

TEST(ImageComparison, ReadsRgbaFilesAsRgb)
{
    osg::ref_ptr<osg::Image> rgba = new osg::Image;
    rgba->allocateImage(3, 2, 1, GL_RGBA, GL_UNSIGNED_BYTE);
    for (int i = 0; i < 6; ++i)
    {
        unsigned char* p = rgba->data() + 4 * i;
        p[0] = static_cast<unsigned char>(10 * i);
        p[1] = 200;
        p[2] = 7;
        p[3] = 128;
    }
    const std::string file = std::string(OSGACTOR_TEST_BINARY_DIR) + "/image-compare/rgba.png";
    osgDB::makeDirectoryForFile(file);
    ASSERT_TRUE(osgDB::writeImageFile(*rgba, file));
    std::string error;
    const osg::ref_ptr<osg::Image> rgb = readRgbImage(file, error);
    ASSERT_TRUE(rgb.valid()) << error;
    EXPECT_TRUE(isRgb8(*rgb));
    EXPECT_EQ(int(rgb->data(2, 1)[0]), 50);
    EXPECT_EQ(int(rgb->data(2, 1)[1]), 200);
    EXPECT_EQ(int(rgb->data(2, 1)[2]), 7);
}
