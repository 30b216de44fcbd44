#include "ImageCompare.h"

#include <osgDB/FileUtils>
#include <osgDB/ReadFile>
#include <osgDB/WriteFile>

#include <algorithm>
#include <cstdlib>
#include <iomanip>
#include <sstream>

namespace osgActor {
namespace test {

namespace {

bool isRgb8(const osg::Image& image)
{
    return image.getPixelFormat() == GL_RGB && image.getDataType() == GL_UNSIGNED_BYTE && image.r() == 1 &&
           image.getPacking() == 1;
}

std::string describe(const osg::Image& image)
{
    std::ostringstream text;
    text << image.s() << "x" << image.t() << (isRgb8(image) ? " RGB8" : " (not 8-bit RGB)");
    return text.str();
}

bool writePng(const osg::Image& image, const std::string& file)
{
    osgDB::makeDirectoryForFile(file);
    return osgDB::writeImageFile(image, file);
}

} // namespace

ImageDifference compareImages(const osg::Image& actual, const osg::Image& reference, int threshold)
{
    ImageDifference result;
    if (!isRgb8(actual) || !isRgb8(reference) || actual.s() != reference.s() || actual.t() != reference.t())
    {
        result.whyNotComparable = "the image is " + describe(actual) + ", the reference " + describe(reference);
        return result;
    }
    result.comparable = true;
    result.numPixels = unsigned(actual.s() * actual.t());
    result.diffImage = new osg::Image;
    result.diffImage->allocateImage(actual.s(), actual.t(), 1, GL_RGB, GL_UNSIGNED_BYTE);

    const unsigned char* a = actual.data();
    const unsigned char* r = reference.data();
    unsigned char* d = result.diffImage->data();
    for (unsigned i = 0; i < result.numPixels; ++i, a += 3, r += 3, d += 3)
    {
        int largest = 0;
        for (int c = 0; c < 3; ++c) largest = std::max(largest, std::abs(int(a[c]) - int(r[c])));
        result.maxChannelDifference = std::max(result.maxChannelDifference, largest);
        const bool differs = largest > threshold;
        if (differs) ++result.numDiffering;
        const unsigned char grey = static_cast<unsigned char>((int(r[0]) + int(r[1]) + int(r[2])) / 12);
        d[0] = differs ? 255 : grey;
        d[1] = differs ? 0 : grey;
        d[2] = differs ? 0 : grey;
    }
    return result;
}

osg::ref_ptr<osg::Image> readRgbImage(const std::string& file)
{
    osg::ref_ptr<osg::Image> image = osgDB::readRefImageFile(file);
    if (!image || !isRgb8(*image)) return nullptr;
    return image;
}

::testing::AssertionResult matchesReference(const osg::Image& actual, const std::string& name, int threshold,
                                            double maxFraction)
{
    const std::string referenceFile = std::string(OSGACTOR_TEST_SOURCE_DIR) + "/render/references/" + name + ".png";
    const char* update = std::getenv("OSGACTOR_UPDATE_REFERENCES");
    if (update != nullptr && std::string(update) == "1")
    {
        if (!writePng(actual, referenceFile))
            return ::testing::AssertionFailure() << "cannot write the new reference " << referenceFile;
        std::cerr << "wrote new reference " << referenceFile << ": look at it before committing it\n";
        return ::testing::AssertionSuccess();
    }

    const osg::ref_ptr<osg::Image> reference = readRgbImage(referenceFile);
    if (!reference)
        return ::testing::AssertionFailure() << "cannot read the reference " << referenceFile
                                             << " as an RGB PNG (make it with OSGACTOR_UPDATE_REFERENCES=1)";

    const ImageDifference difference = compareImages(actual, *reference, threshold);
    if (difference.comparable && difference.differingFraction() <= maxFraction)
        return ::testing::AssertionSuccess();

    const std::string failureDir = std::string(OSGACTOR_TEST_BINARY_DIR) + "/image-failures/";
    const std::string actualFile = failureDir + name + "_actual.png";
    const std::string diffFile = failureDir + name + "_diff.png";
    ::testing::AssertionResult failure = ::testing::AssertionFailure();
    failure << "image \"" << name << "\" does not match " << referenceFile << ": ";
    if (!difference.comparable) failure << difference.whyNotComparable;
    else
        failure << std::fixed << std::setprecision(2) << difference.numDiffering << " of " << difference.numPixels
                << " pixels ("
                << 100.0 * difference.differingFraction() << "%, at most " << 100.0 * maxFraction
                << "% allowed) differ by more than " << threshold << " (largest difference "
                << difference.maxChannelDifference << ")";
    failure << "; actual image: " << (writePng(actual, actualFile) ? actualFile : "(could not be written)");
    if (difference.diffImage)
        failure << ", diff image: "
                << (writePng(*difference.diffImage, diffFile) ? diffFile : "(could not be written)");
    return failure;
}

} // namespace test
} // namespace osgActor
