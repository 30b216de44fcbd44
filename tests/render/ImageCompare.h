/* Image regression helpers: compare a rendered image with a reference PNG, with a tolerance. */
#ifndef OSGACTOR_TESTS_RENDER_IMAGECOMPARE_H
#define OSGACTOR_TESTS_RENDER_IMAGECOMPARE_H 1

#include <osg/Image>

#include <gtest/gtest.h>

#include <string>

namespace osgActor {
namespace test {

/** How two RGB images differ. */
struct ImageDifference
{
    /** False when the sizes or pixel formats differ; nothing else is then filled in. */
    bool comparable = false;
    std::string whyNotComparable;
    unsigned numPixels = 0;
    /** Pixels where some channel differs by more than the threshold. */
    unsigned numDiffering = 0;
    /** The largest difference of one channel anywhere, 0..255. */
    int maxChannelDifference = 0;
    /** The reference, dimmed, with the differing pixels in red. */
    osg::ref_ptr<osg::Image> diffImage;

    double differingFraction() const { return numPixels > 0 ? double(numDiffering) / numPixels : 0.0; }
};

/** Compares two 8-bit RGB images pixel by pixel; a pixel differs when a channel differs by more than threshold. */
ImageDifference compareImages(const osg::Image& actual, const osg::Image& reference, int threshold);

/** Compares an image with tests/render/references/<name>.png: it matches when at most maxFraction of its pixels
  * differ by more than threshold in a channel. On failure the actual image and the diff image are written to
  * <build>/tests/render/image-failures/<name>_actual.png and <name>_diff.png, and the message names them.
  *
  * With OSGACTOR_UPDATE_REFERENCES=1 in the environment the image is written as the new reference instead (and
  * the check passes): look at every image written that way before committing it. */
::testing::AssertionResult matchesReference(const osg::Image& actual, const std::string& name, int threshold = 24,
                                            double maxFraction = 0.003);

/** Reads a PNG as 8-bit RGB; null if it cannot be read or is in another format. */
osg::ref_ptr<osg::Image> readRgbImage(const std::string& file);

} // namespace test
} // namespace osgActor

#endif
