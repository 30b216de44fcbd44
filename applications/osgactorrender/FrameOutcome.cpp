#include "FrameOutcome.h"

#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>

namespace osgActorRender {

namespace {

const char* const kStatusNames[] = {"rendered", "matches", "differs", "kept", "changed", "new"};

} // namespace

std::string encodeFrameOutcome(const FrameOutcome& outcome)
{
    const osgActor::ImageComparison& c = outcome.comparison;
    std::ostringstream line;
    line << "frame " << outcome.frame << ' ' << kStatusNames[outcome.status] << ' ' << (c.comparable ? 1 : 0) << ' '
         << c.tolerance << ' ' << c.numPixels << ' ' << c.numOverTolerance << ' ' << c.maxChannelDifference << ' '
         << std::setprecision(17) << (std::isinf(c.psnr) ? -1.0 : c.psnr) << ' ' << c.whyNotComparable;
    return line.str();
}

bool decodeFrameOutcome(const std::string& line, FrameOutcome& outcome)
{
    std::istringstream in(line);
    std::string word;
    std::string status;
    int comparable = 0;
    osgActor::ImageComparison& c = outcome.comparison;
    if (!(in >> word >> outcome.frame >> status >> comparable >> c.tolerance >> c.numPixels >> c.numOverTolerance >>
          c.maxChannelDifference >> c.psnr) ||
        word != "frame")
        return false;
    if (c.psnr < 0.0) c.psnr = std::numeric_limits<double>::infinity();
    c.comparable = comparable != 0;
    in >> std::ws;
    std::getline(in, c.whyNotComparable);
    for (int s = FrameOutcome::RENDERED; s <= FrameOutcome::REFERENCE_NEW; ++s)
    {
        if (status == kStatusNames[s])
        {
            outcome.status = FrameOutcome::Status(s);
            return true;
        }
    }
    return false;
}

} // namespace osgActorRender
