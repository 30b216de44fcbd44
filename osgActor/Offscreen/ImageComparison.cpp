#include <osgActor/Offscreen/ImageComparison>

#include <osgDB/ReadFile>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <sstream>

namespace osgActor {

namespace {

std::string describe(const osg::Image& image)
{
    std::ostringstream text;
    text << image.s() << "x" << image.t();
    if (!isRgb8(image)) text << " (not 8-bit RGB)";
    return text.str();
}

/** The largest difference between the channels of two RGB pixels. */
int channelDifference(const unsigned char* a, const unsigned char* b)
{
    int largest = 0;
    for (int c = 0; c < 3; ++c) largest = std::max(largest, std::abs(int(a[c]) - int(b[c])));
    return largest;
}

bool sameSizeRgb8(const osg::Image& rendered, const osg::Image& reference, std::string& why)
{
    if (isRgb8(rendered) && isRgb8(reference) && rendered.s() == reference.s() && rendered.t() == reference.t())
        return true;
    why = "the render is " + describe(rendered) + ", the reference " + describe(reference);
    return false;
}

} // namespace

double ImageComparison::getShareOverTolerance() const
{
    return numPixels > 0 ? double(numOverTolerance) / double(numPixels) : 0.0;
}

bool ImageComparison::matches(double allowedShare) const
{
    return comparable && getShareOverTolerance() <= allowedShare;
}

bool isRgb8(const osg::Image& image)
{
    return image.getPixelFormat() == GL_RGB && image.getDataType() == GL_UNSIGNED_BYTE && image.r() == 1 &&
           image.s() > 0 && image.t() > 0 && image.data() != nullptr;
}

ImageComparison compareImages(const osg::Image& rendered, const osg::Image& reference, int tolerance)
{
    ImageComparison result;
    result.tolerance = tolerance;
    if (!sameSizeRgb8(rendered, reference, result.whyNotComparable)) return result;
    result.comparable = true;
    result.numPixels = unsigned(rendered.s()) * unsigned(rendered.t());

    double sumOfSquares = 0.0;
    for (int y = 0; y < rendered.t(); ++y)
    {
        // Row by row: osg::Image rows may be padded (packing).
        const unsigned char* a = rendered.data(0, y);
        const unsigned char* b = reference.data(0, y);
        for (int x = 0; x < rendered.s(); ++x, a += 3, b += 3)
        {
            for (int c = 0; c < 3; ++c)
            {
                const double d = double(a[c]) - double(b[c]);
                sumOfSquares += d * d;
            }
            const int largest = channelDifference(a, b);
            result.maxChannelDifference = std::max(result.maxChannelDifference, largest);
            if (largest > tolerance) ++result.numOverTolerance;
        }
    }
    const double meanSquare = sumOfSquares / (3.0 * double(result.numPixels));
    result.psnr = meanSquare > 0.0 ? 10.0 * std::log10(255.0 * 255.0 / meanSquare)
                                   : std::numeric_limits<double>::infinity();
    return result;
}

osg::ref_ptr<osg::Image> makeDiffImage(const osg::Image& rendered, const osg::Image& reference, int tolerance)
{
    std::string why;
    if (!sameSizeRgb8(rendered, reference, why)) return nullptr;

    // 16 levels above zero (or above the tolerance) reach full intensity: a difference of 3 in 255 still shows.
    const int kGain = 8;
    osg::ref_ptr<osg::Image> diff = new osg::Image;
    diff->allocateImage(rendered.s(), rendered.t(), 1, GL_RGB, GL_UNSIGNED_BYTE);
    for (int y = 0; y < rendered.t(); ++y)
    {
        const unsigned char* a = rendered.data(0, y);
        const unsigned char* b = reference.data(0, y);
        unsigned char* out = diff->data(0, y);
        for (int x = 0; x < rendered.s(); ++x, a += 3, b += 3, out += 3)
        {
            for (int c = 0; c < 3; ++c) out[c] = static_cast<unsigned char>(b[c] / 3);
            const int d = channelDifference(a, b);
            if (d > tolerance)
            {
                out[0] = static_cast<unsigned char>(std::min(255, 128 + kGain * (d - tolerance)));
                out[1] = 0;
                out[2] = 0;
            }
            else if (d > 0)
                out[2] = static_cast<unsigned char>(std::min(255, 128 + kGain * d));
        }
    }
    return diff;
}

osg::ref_ptr<osg::Image> readRgbImage(const std::string& file, std::string& error)
{
    const osg::ref_ptr<osg::Image> image = osgDB::readRefImageFile(file);
    if (!image || image->data() == nullptr)
    {
        error = "cannot read the image \"" + file + "\" (missing, damaged, or in a format no osgDB plugin reads)";
        return nullptr;
    }
    if (isRgb8(*image)) return image;
    if (image->getPixelFormat() != GL_RGBA || image->getDataType() != GL_UNSIGNED_BYTE || image->r() != 1)
    {
        error = "the image \"" + file + "\" is not 8-bit RGB or RGBA";
        return nullptr;
    }
    osg::ref_ptr<osg::Image> rgb = new osg::Image;
    rgb->allocateImage(image->s(), image->t(), 1, GL_RGB, GL_UNSIGNED_BYTE);
    for (int y = 0; y < image->t(); ++y)
    {
        const unsigned char* in = image->data(0, y);
        unsigned char* out = rgb->data(0, y);
        for (int x = 0; x < image->s(); ++x, in += 4, out += 3)
            for (int c = 0; c < 3; ++c) out[c] = in[c];
    }
    return rgb;
}

} // namespace osgActor
