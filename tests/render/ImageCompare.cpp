#include "ImageCompare.h"
#include "TestFigure.h"

#include <osgDB/FileUtils>
#include <osgDB/WriteFile>

#include <cstdlib>
#include <iomanip>

namespace osgActor {
namespace test {

namespace {

bool writePng(const osg::Image& image, const std::string& file)
{
    osgDB::makeDirectoryForFile(file);
    return osgDB::writeImageFile(image, file);
}

} // namespace

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

    std::string error;
    const osg::ref_ptr<osg::Image> reference = readRgbImage(referenceFile, error);
    if (!reference)
        return ::testing::AssertionFailure() << error << " (make it with OSGACTOR_UPDATE_REFERENCES=1)";

    const ImageComparison comparison = compareImages(actual, *reference, threshold);
    if (comparison.matches(maxFraction)) return ::testing::AssertionSuccess();

    const std::string failureDir = std::string(OSGACTOR_TEST_BINARY_DIR) + "/image-failures/";
    const std::string actualFile = failureDir + name + "_actual.png";
    const std::string diffFile = failureDir + name + "_diff.png";
    ::testing::AssertionResult failure = ::testing::AssertionFailure();
    failure << "image \"" << name << "\" does not match " << referenceFile << ": ";
    if (!comparison.comparable) failure << comparison.whyNotComparable;
    else
        failure << std::fixed << std::setprecision(2) << comparison.numOverTolerance << " of " << comparison.numPixels
                << " pixels (" << 100.0 * comparison.getShareOverTolerance() << "%, at most " << 100.0 * maxFraction
                << "% allowed) differ by more than " << threshold << " (largest difference "
                << comparison.maxChannelDifference << ")";
    failure << "; actual image: " << (writePng(actual, actualFile) ? actualFile : "(could not be written)");
    const osg::ref_ptr<osg::Image> diff = makeDiffImage(actual, *reference, threshold);
    if (diff) failure << ", diff image: " << (writePng(*diff, diffFile) ? diffFile : "(could not be written)");
    return failure;
}

::testing::AssertionResult isTheSameBytesCovering(const osg::Image& actual, const osg::Image& expected,
                                                  const osg::Vec4& background, double minShare)
{
    const ImageComparison difference = compareImages(actual, expected, 0);
    if (!difference.comparable) return ::testing::AssertionFailure() << "the images cannot be compared";
    if (difference.numOverTolerance != 0 || difference.maxChannelDifference != 0)
        return ::testing::AssertionFailure() << difference.numOverTolerance << " pixels differ, by up to "
                                             << difference.maxChannelDifference;
    const unsigned drawn = countDrawnPixels(actual, background);
    if (drawn <= minShare * actual.s() * actual.t())
        return ::testing::AssertionFailure() << "the same bytes, but only " << drawn << " pixels are drawn";
    return ::testing::AssertionSuccess();
}

} // namespace test
} // namespace osgActor
