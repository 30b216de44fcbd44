// The image comparison the regression tests rely on: it must tell images apart, and tolerate what it should.
#include "ImageCompare.h"

#include <gtest/gtest.h>

#include <cstdlib>

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

TEST(ImageCompare, RefusesImagesOfDifferentSizes)
{
    const ImageDifference difference = compareImages(*solidImage(4, 4, 0, 0, 0), *solidImage(4, 5, 0, 0, 0), 0);
    EXPECT_FALSE(difference.comparable);
    EXPECT_NE(difference.whyNotComparable.find("4x4"), std::string::npos) << difference.whyNotComparable;
}

TEST(ImageCompare, RefusesImagesThatAreNotRgb8)
{
    osg::ref_ptr<osg::Image> rgba = new osg::Image;
    rgba->allocateImage(4, 4, 1, GL_RGBA, GL_UNSIGNED_BYTE);
    EXPECT_FALSE(compareImages(*rgba, *solidImage(4, 4, 0, 0, 0), 0).comparable);
}

TEST(ImageCompare, MissingReferenceFailsAndSaysHowToMakeIt)
{
    const char* update = std::getenv("OSGACTOR_UPDATE_REFERENCES");
    if (update != nullptr && std::string(update) == "1") GTEST_SKIP() << "writing references";
    const ::testing::AssertionResult result = matchesReference(*solidImage(4, 4, 0, 0, 0), "no_such_reference");
    EXPECT_FALSE(result);
    EXPECT_NE(std::string(result.message()).find("OSGACTOR_UPDATE_REFERENCES"), std::string::npos);
}

TEST(ImageCompare, IdenticalImagesDoNotDiffer)
{
    const ImageDifference difference = compareImages(*solidImage(8, 6, 10, 20, 30), *solidImage(8, 6, 10, 20, 30), 0);
    ASSERT_TRUE(difference.comparable);
    EXPECT_EQ(difference.numPixels, 48u);
    EXPECT_EQ(difference.numDiffering, 0u);
    EXPECT_EQ(difference.maxChannelDifference, 0);
}

TEST(ImageCompare, CountsPixelsBeyondTheThresholdOnly)
{
    osg::ref_ptr<osg::Image> actual = solidImage(10, 10, 100, 100, 100);
    const osg::ref_ptr<osg::Image> reference = solidImage(10, 10, 100, 100, 100);
    actual->data(1, 2)[0] = 110; // within a threshold of 10
    actual->data(3, 4)[2] = 111; // beyond it
    actual->data(5, 6)[1] = 0;   // far beyond it
    const ImageDifference difference = compareImages(*actual, *reference, 10);
    ASSERT_TRUE(difference.comparable);
    EXPECT_EQ(difference.numDiffering, 2u);
    EXPECT_EQ(difference.maxChannelDifference, 100);
    EXPECT_DOUBLE_EQ(difference.differingFraction(), 0.02);
    // The diff image marks exactly the differing pixels in red.
    ASSERT_TRUE(difference.diffImage.valid());
    EXPECT_EQ(difference.diffImage->data(3, 4)[0], 255);
    EXPECT_EQ(difference.diffImage->data(3, 4)[1], 0);
    EXPECT_NE(difference.diffImage->data(1, 2)[0], 255);
}
