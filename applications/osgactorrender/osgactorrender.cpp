// osgactorrender: renders any scene osgDB can read into PNG images offscreen, through OSMesa, with no display, and
// compares them with reference images.
//
//   osgactorrender data/humanoid.actor -o out/frame_%04d.png --frames 0 47 --contact-sheet out/sheet.png
//   osgactorrender scene.osgt --frames 0 47 --compare refs/frame_%04d.png --diff out/diff_%04d.png --jobs 4
//
// Exit status (as diff's and cmp's): 0 done, every frame compared matches; 1 a frame differs from its reference
// (or between two renders, --check-determinism); 2 bad options, unreadable or unwritable files, no GL context.
#include "JobRunner.h"
#include "OutputPattern.h"
#include "PartRenderer.h"
#include "RenderOptions.h"
#include "RunSummary.h"
#include "ScratchFolder.h"

#include <osg/ArgumentParser>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <sstream>

using namespace osgActorRender;

namespace {

const int kDiffers = 1;
const int kFailed = 2;

int fail(const std::string& message)
{
    std::cerr << "osgactorrender: " << message << std::endl;
    return kFailed;
}

/** Every pattern parses, and names each frame apart when there are several. */
bool checkPatterns(const RenderOptions& options, std::string& error)
{
    const bool severalFrames = options.getNumFrames() > 1;
    const std::pair<std::string, bool> patterns[] = {{options.outputPattern, options.writeFrames},
                                                     {options.referencePattern, options.comparing()},
                                                     {options.diffPattern, !options.diffPattern.empty()},
                                                     {options.jobScratchPattern, !options.jobScratchPattern.empty()}};
    for (const auto& pattern : patterns)
    {
        if (!pattern.second) continue;
        OutputPattern parsed;
        if (!parsed.parse(pattern.first, error)) return false;
        if (severalFrames && !parsed.hasFrameField())
        {
            error = "the pattern \"" + pattern.first + "\" has no frame number (%04d) for " +
                    std::to_string(options.getNumFrames()) + " frames";
            return false;
        }
    }
    return true;
}

/** A --jobs child's sink: one line per frame on the report descriptor. */
class ReportLines : public FrameSink
{
public:
    explicit ReportLines(std::FILE* stream) : _stream(stream) {}
    void frameDone(const FrameOutcome& outcome, const osg::Image*) override
    {
        _anyDiffers = _anyDiffers || outcome.differs();
        write(encodeFrameOutcome(outcome));
    }
    void write(const std::string& line)
    {
        std::fprintf(_stream, "%s\n", line.c_str());
        std::fflush(_stream);
    }
    bool anyDiffers() const { return _anyDiffers; }

private:
    std::FILE* _stream;
    bool _anyDiffers = false;
};

/** A child of a --jobs run: its part, reported frame by frame to the parent, which says what happened. */
int runJobChild(const RenderOptions& options)
{
    std::FILE* stream = fdopen(options.jobReportFd, "w");
    if (stream == nullptr) return fail("--job-report-fd " + std::to_string(options.jobReportFd) + " is not open");
    ReportLines report(stream);
    unsigned first = 0;
    unsigned last = 0;
    options.getPartFrames(options.part, options.numParts, first, last);
    if (first > last) return 0;

    std::string error;
    if (options.checkDeterminism)
    {
        int differing = -1;
        if (!checkPartDeterminism(options, first, last, [&report] { report.write("step"); }, differing, error))
            return fail(error);
        if (differing < 0) return 0;
        report.write("nondeterministic " + std::to_string(differing));
        return kDiffers;
    }
    if (!renderPart(options, first, last, options.jobScratchPattern, options.jobScratchAll, report, error))
        return fail(error);
    return report.anyDiffers() ? kDiffers : 0;
}

/** The command line for the children: this one without --jobs n. */
std::vector<std::string> withoutJobs(const std::vector<std::string>& commandLine)
{
    std::vector<std::string> arguments;
    for (size_t i = 0; i < commandLine.size(); ++i)
    {
        if (commandLine[i] == "--jobs") ++i;
        else arguments.push_back(commandLine[i]);
    }
    return arguments;
}

/** Runs the children, feeding the summary (frames) or the determinism result, and prints what they said on
  * stderr. The exit status the children's endings call for: 0, or 2 when one failed, crashed or ended without
  * reporting every frame of its part. */
int runJobs(const std::vector<std::string>& arguments, unsigned numJobs, unsigned numFrames, bool checkingDeterminism,
            RunSummary& summary, int& firstNondeterministic)
{
    JobRunner runner(arguments, numJobs);
    std::string error;
    unsigned numSteps = 0;
    const bool started = runner.run(
        [&](const std::string& line) {
            FrameOutcome outcome;
            int frame = -1;
            if (line == "step")
            {
                ++numSteps;
                summary.step();
            }
            else if (std::sscanf(line.c_str(), "nondeterministic %d", &frame) == 1)
                firstNondeterministic = firstNondeterministic < 0 ? frame : std::min(firstNondeterministic, frame);
            else if (decodeFrameOutcome(line, outcome)) summary.frameDone(outcome, nullptr);
        },
        error);
    summary.endProgress();
    for (const std::string& message : runner.getMessages()) std::cerr << message << "\n";
    if (!started) return fail(error);
    if (runner.getWorstStatus() >= kFailed) return kFailed;
    // A child that ended otherwise (killed, or not this program) must not pass for one whose frames all matched.
    const bool complete = checkingDeterminism ? firstNondeterministic >= 0 || numSteps == 2 * numFrames
                                              : summary.getNumFramesDone() == numFrames;
    if (!complete)
        return fail("the jobs ended without reporting every frame (" +
                    std::to_string(checkingDeterminism ? numSteps : summary.getNumFramesDone()) + " of " +
                    std::to_string(checkingDeterminism ? 2 * numFrames : numFrames) + ")");
    return 0;
}

} // namespace

int main(int argc, char** argv)
{
    const auto start = std::chrono::steady_clock::now();
    const std::vector<std::string> commandLine(argv + 1, argv + argc); // before the parser takes the options out
    osg::ArgumentParser arguments(&argc, argv);
    describeRenderOptions(arguments);
    if (arguments.read("-h") || arguments.read("--help"))
    {
        arguments.getApplicationUsage()->write(std::cout, osg::ApplicationUsage::COMMAND_LINE_OPTION);
        return 0;
    }

    RenderOptions options;
    std::string error;
    if (!parseRenderOptions(arguments, options, error)) return fail(error + " (--help lists the options)");
    if (!checkPatterns(options, error)) return fail(error);
    if (options.isJobChild()) return runJobChild(options);

    unsigned first = 0;
    unsigned last = 0;
    options.getPartFrames(options.part, options.numParts, first, last);
    if (first > last)
    {
        std::cout << "osgactorrender: part " << options.part << "/" << options.numParts << " of "
                  << options.getNumFrames() << " frames has no frame" << std::endl;
        return 0;
    }
    const unsigned numFrames = last - first + 1;
    const unsigned numJobs = std::min(options.jobs, numFrames);
    RunSummary summary(options, first, last,
                       numFrames > 1 && (options.forceProgress || ProgressBar::isTerminal(stderr)));

    // Frames the sheets read back from disk, where -o does not put them: a --jobs parent's contact sheet (every
    // frame) and the comparison sheet (the frames that differ).
    ScratchFolder scratch;
    const bool scratchEveryFrame = numJobs > 1 && !options.contactSheet.empty();
    if (!options.writeFrames && (scratchEveryFrame || !options.compareSheet.empty()) && !scratch.create(error))
        return fail(error);
    const std::string renderFiles = options.writeFrames ? options.outputPattern : scratch.getFramePattern();

    int status = 0;
    int firstNondeterministic = -1;
    if (numJobs > 1)
    {
        std::vector<std::string> childArguments = withoutJobs(commandLine);
        if (!scratch.getFramePattern().empty())
        {
            childArguments.insert(childArguments.end(), {"--job-scratch", scratch.getFramePattern()});
            if (scratchEveryFrame) childArguments.push_back("--job-scratch-all");
        }
        status = runJobs(childArguments, numJobs, numFrames, options.checkDeterminism, summary,
                         firstNondeterministic);
    }
    else if (options.checkDeterminism)
    {
        if (!checkPartDeterminism(options, first, last, [&summary] { summary.step(); }, firstNondeterministic,
                                  error))
            status = (summary.endProgress(), fail(error));
    }
    else if (!renderPart(options, first, last, scratch.getFramePattern(), false, summary, error))
        status = (summary.endProgress(), fail(error));
    if (status != 0) return status;

    if (options.checkDeterminism)
    {
        summary.endProgress();
        if (firstNondeterministic >= 0)
        {
            std::cout << "osgactorrender: frame " << firstNondeterministic
                      << " differs between two renders of the same scene: something in it changes from run to run "
                         "(a callback reading the clock or an unseeded random generator; see "
                         "docs/regression-renders.md)"
                      << std::endl;
            return kDiffers;
        }
        std::cout << "osgactorrender: frames " << options.frameNumber(first) << ".." << options.frameNumber(last)
                  << " are the same bytes on both renders" << std::endl;
        return 0;
    }

    std::ostringstream lines;
    status = summary.finish(renderFiles, lines, error);
    std::cout << lines.str() << std::flush;
    if (status == kFailed) return fail(error);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::cout << "osgactorrender: " << numFrames << " frame(s) of " << options.settings.width << "x"
              << options.settings.height << " in " << seconds << " s (" << numFrames / seconds
              << " frames per second, " << numJobs << (numJobs > 1 ? " processes" : " process") << ")" << std::endl;
    return status;
}
