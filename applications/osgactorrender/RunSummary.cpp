#include "RunSummary.h"

#include "ImageFile.h"
#include "OutputPattern.h"

#include <osgActor/Offscreen/ImageComparison>

#include <osgDB/FileUtils>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <limits>
#include <sstream>

namespace osgActorRender {

namespace {

std::string formatPsnr(double psnr)
{
    if (std::isinf(psnr)) return "inf";
    std::ostringstream text;
    text << std::fixed << std::setprecision(2) << psnr;
    return text.str();
}

const char* statusName(FrameOutcome::Status status)
{
    switch (status)
    {
    case FrameOutcome::RENDERED: return "rendered";
    case FrameOutcome::MATCHES: return "matches";
    case FrameOutcome::DIFFERS: return "differs";
    case FrameOutcome::REFERENCE_KEPT: return "reference kept";
    case FrameOutcome::REFERENCE_CHANGED: return "reference changed";
    case FrameOutcome::REFERENCE_NEW: return "reference new";
    }
    return "";
}

} // namespace

RunSummary::RunSummary(const RenderOptions& options, unsigned first, unsigned last, bool showProgress)
    : _options(options), _first(first), _last(last),
      _progress((last - first + 1) * (options.checkDeterminism ? 2u : 1u), showProgress)
{
    if (!options.contactSheet.empty())
    {
        _contactSheet.reset(new osgActor::ContactSheet(last - first + 1, options.sheetColumns, options.settings.width,
                                                       options.settings.height, options.sheetTileWidth,
                                                       options.settings.background));
        _tileFilled.assign(last - first + 1, false);
    }
}

void RunSummary::frameDone(const FrameOutcome& outcome, const osg::Image* image)
{
    _outcomes.push_back(outcome);
    const unsigned tile = outcome.frame - _options.frameNumber(_first);
    if (_contactSheet && image != nullptr && tile < _tileFilled.size())
        _tileFilled[tile] = _contactSheet->addFrame(tile, *image);
    _progress.step();
}

int RunSummary::finish(const std::string& renderFiles, std::ostream& out, std::string& error)
{
    _progress.finish();
    std::sort(_outcomes.begin(), _outcomes.end(),
              [](const FrameOutcome& a, const FrameOutcome& b) { return a.frame < b.frame; });
    std::vector<const FrameOutcome*> differing;
    for (const FrameOutcome& outcome : _outcomes)
        if (outcome.differs()) differing.push_back(&outcome);

    if (_contactSheet && !writeContactSheet(renderFiles, error)) return 2;
    if (!_options.compareSheet.empty() && !writeCompareSheet(differing, renderFiles, error)) return 2;
    if (!_options.reportFile.empty() && !writeReport(error)) return 2;

    const OutputPattern output = OutputPattern::fromChecked(_options.outputPattern);
    if (_options.writeFrames && !_outcomes.empty())
    {
        out << "osgactorrender: wrote " << output.format(_outcomes.front().frame);
        if (_outcomes.size() > 1) out << " .. " << output.format(_outcomes.back().frame);
        out << "\n";
    }
    if (_contactSheet) out << "osgactorrender: wrote contact sheet " << _options.contactSheet << "\n";
    if (!_options.comparing()) return 0;

    const std::string& references = _options.referencePattern;
    if (_options.rules.updateReferences)
    {
        unsigned changed = 0;
        unsigned created = 0;
        for (const FrameOutcome& outcome : _outcomes)
        {
            changed += outcome.status == FrameOutcome::REFERENCE_CHANGED ? 1 : 0;
            created += outcome.status == FrameOutcome::REFERENCE_NEW ? 1 : 0;
        }
        out << "osgactorrender: updated " << changed + created << " of " << _outcomes.size() << " references "
            << references << " (" << changed << " changed, " << created << " new; the others match and were kept)"
            << (changed + created > 0 ? ": look at them before committing them" : "") << "\n";
        return 0;
    }

    for (const FrameOutcome* outcome : differing) printDifferingFrame(*outcome, out);
    if (!_options.compareSheet.empty() && !differing.empty())
        out << "osgactorrender: wrote comparison sheet " << _options.compareSheet
            << " (per differing frame: reference, render, diff)\n";
    if (!differing.empty())
    {
        out << "osgactorrender: " << differing.size() << " of " << _outcomes.size() << " frames differ from "
            << references << " (tolerance " << _options.rules.tolerance << ")\n";
        return 1;
    }
    int largest = 0;
    double lowestPsnr = std::numeric_limits<double>::infinity();
    for (const FrameOutcome& outcome : _outcomes)
    {
        largest = std::max(largest, outcome.comparison.maxChannelDifference);
        lowestPsnr = std::min(lowestPsnr, outcome.comparison.psnr);
    }
    out << "osgactorrender: all " << _outcomes.size() << " frames match " << references << " (tolerance "
        << _options.rules.tolerance << "; largest difference " << largest << ", lowest PSNR "
        << formatPsnr(lowestPsnr) << " dB)\n";
    return 0;
}

void RunSummary::printDifferingFrame(const FrameOutcome& outcome, std::ostream& out) const
{
    const osgActor::ImageComparison& c = outcome.comparison;
    out << "osgactorrender: frame " << outcome.frame << " differs from "
        << OutputPattern::fromChecked(_options.referencePattern).format(outcome.frame) << ": ";
    if (!c.comparable)
    {
        out << c.whyNotComparable << "\n";
        return;
    }
    out << c.numOverTolerance << " of " << c.numPixels << " pixels (" << std::fixed << std::setprecision(3)
        << 100.0 * c.getShareOverTolerance() << "%) over the tolerance of " << c.tolerance
        << ", largest difference " << c.maxChannelDifference << ", PSNR " << formatPsnr(c.psnr) << " dB";
    out.unsetf(std::ios::floatfield);
    if (!_options.diffPattern.empty())
        out << "; diff " << OutputPattern::fromChecked(_options.diffPattern).format(outcome.frame);
    out << "\n";
}

bool RunSummary::writeContactSheet(const std::string& renderFiles, std::string& error)
{
    const OutputPattern files = OutputPattern::fromChecked(renderFiles);
    for (unsigned tile = 0; tile < _tileFilled.size(); ++tile)
    {
        if (_tileFilled[tile]) continue;
        // Rendered in another process: the frame is read back from where it wrote it.
        const osg::ref_ptr<osg::Image> frame =
            osgActor::readRgbImage(files.format(_options.frameNumber(_first + tile)), error);
        if (!frame || !_contactSheet->addFrame(tile, *frame))
        {
            if (error.empty()) error = "a rendered frame does not fit the contact sheet";
            return false;
        }
    }
    return writeImage(*_contactSheet->getImage(), _options.contactSheet, error);
}

bool RunSummary::writeCompareSheet(const std::vector<const FrameOutcome*>& differing, const std::string& renderFiles,
                                   std::string& error)
{
    if (differing.empty()) return true; // nothing to show: no sheet, rather than an empty one
    const OutputPattern references = OutputPattern::fromChecked(_options.referencePattern);
    const OutputPattern renders = OutputPattern::fromChecked(renderFiles);
    const int width = _options.settings.width;
    const int height = _options.settings.height;
    osgActor::ContactSheet sheet(unsigned(differing.size()) * 3u, 3u, width, height, _options.sheetTileWidth,
                                 _options.settings.background);
    for (size_t row = 0; row < differing.size(); ++row)
    {
        const unsigned frame = differing[row]->frame;
        const osg::ref_ptr<osg::Image> reference = osgActor::readRgbImage(references.format(frame), error);
        const osg::ref_ptr<osg::Image> render = osgActor::readRgbImage(renders.format(frame), error);
        if (!reference || !render) return false;
        const osg::ref_ptr<osg::Image> diff = osgActor::makeDiffImage(*render, *reference, _options.rules.tolerance);
        // A reference of another size has no tile of this size and no diff: its row shows the render alone.
        sheet.addFrame(unsigned(3 * row), *reference);
        sheet.addFrame(unsigned(3 * row + 1), *render);
        if (diff) sheet.addFrame(unsigned(3 * row + 2), *diff);
    }
    return writeImage(*sheet.getImage(), _options.compareSheet, error);
}

bool RunSummary::writeReport(std::string& error) const
{
    osgDB::makeDirectoryForFile(_options.reportFile);
    std::ofstream report(_options.reportFile);
    report << "frame,status,max_channel_difference,pixels_over_tolerance,share_over_tolerance,psnr_db\n";
    for (const FrameOutcome& outcome : _outcomes)
    {
        const osgActor::ImageComparison& c = outcome.comparison;
        report << outcome.frame << "," << statusName(outcome.status) << ",";
        if (c.comparable)
            report << c.maxChannelDifference << "," << c.numOverTolerance << "," << std::setprecision(6)
                   << c.getShareOverTolerance() << "," << formatPsnr(c.psnr);
        else report << ",,,";
        report << "\n";
    }
    if (report.good()) return true;
    error = "cannot write the report \"" + _options.reportFile + "\"";
    return false;
}

} // namespace osgActorRender
