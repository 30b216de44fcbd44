#include "RenderOptions.h"

#include <osg/ApplicationUsage>

#include <cmath>
#include <sstream>

namespace osgActorRender {

void describeRenderOptions(osg::ArgumentParser& arguments)
{
    osg::ApplicationUsage* usage = arguments.getApplicationUsage();
    usage->setApplicationName(arguments.getApplicationName());
    usage->setDescription(arguments.getApplicationName() +
                          " renders any scene osgDB can read (actors, mocap, models) into PNG images offscreen, "
                          "through OSMesa, with no display; and compares them with reference images. Exit status: 0 "
                          "done (every frame matches), 1 a frame differs, 2 bad options or files.");
    usage->setCommandLineUsage(arguments.getApplicationName() + " [options] file ...");
    usage->addCommandLineOption("-h or --help", "Display this information.");
    usage->addCommandLineOption("--size <width> <height>", "Image size in pixels (default 640 480).");
    usage->addCommandLineOption("--fov <degrees>", "Vertical field of view (default 30).");
    usage->addCommandLineOption("--eye <x> <y> <z>", "Camera position (default: framed from what the scene draws).");
    usage->addCommandLineOption("--center <x> <y> <z>",
                                "Point looked at (default: the centre of what the scene draws).");
    usage->addCommandLineOption("--up <x> <y> <z>", "Camera up direction (default 0 0 1).");
    usage->addCommandLineOption("--time <seconds>", "Render one frame at this simulation time (default 0), after "
                                                    "updating the scene at every frame time before it (see --fps).");
    usage->addCommandLineOption("--frames <first> <last>", "Render frames first..last, frame n at time n / fps.");
    usage->addCommandLineOption("--fps <rate>", "Frame rate (default 30): the scene is updated at times 0, 1 / fps, "
                                                "2 / fps, ... up to the first frame rendered, so that players driven "
                                                "by the frame's delta time show what a viewer would.");
    usage->addCommandLineOption("-o or --output <pattern>",
                                "Output PNG file pattern, %04d is the frame number (default frame_%04d.png; with "
                                "--compare, frames are written only when -o is given).");
    usage->addCommandLineOption("--no-frames", "Write no frame images (with --contact-sheet: the sheet only).");
    usage->addCommandLineOption("--background <r> <g> <b>", "Background colour, 0..1 (default 0.2 0.2 0.4).");
    usage->addCommandLineOption("--contact-sheet <file>", "Also write every frame, reduced, into one image.");
    usage->addCommandLineOption("--sheet-columns <n>", "Columns of the contact sheet (default: a square grid).");
    usage->addCommandLineOption("--sheet-tile-width <pixels>", "Width of a frame on the sheets (default 160).");
    usage->addCommandLineOption("--compare <pattern>",
                                "Compare each frame with its reference image (a pattern as -o's): per frame the "
                                "largest channel difference, the share of pixels over --tolerance and the PSNR. "
                                "Exit status 1, with a line per differing frame, if any differs.");
    usage->addCommandLineOption("--tolerance <levels>",
                                "A pixel differs when a channel differs by more than this, of 255 (default 2).");
    usage->addCommandLineOption("--allowed-share <percent>",
                                "A frame still matches with up to this share of differing pixels (default 0).");
    usage->addCommandLineOption("--diff <pattern>", "Write a diff image for each differing frame: the differences, "
                                                    "amplified, in red over a dimmed copy of the reference.");
    usage->addCommandLineOption("--compare-sheet <file>",
                                "Write the differing frames side by side, reduced: reference, render, diff.");
    usage->addCommandLineOption("--report <file.csv>", "Write every frame's figures as CSV.");
    usage->addCommandLineOption("--update-references",
                                "With --compare: write the render as the reference wherever it does not match "
                                "(or none exists), and say how many changed.");
    usage->addCommandLineOption("--check-determinism", "Render the frames twice and report the first frame whose "
                                                       "bytes differ (exit status 1); nothing is written.");
    usage->addCommandLineOption("--jobs <n>", "Render the frames in n processes, each a contiguous part of them with "
                                              "its own OSMesa context (default 1).");
    usage->addCommandLineOption("--part <k>/<n>", "Render only part k of n of the frames (the parts --jobs n renders), "
                                                  "for spreading one sequence over machines.");
    usage->addCommandLineOption("--seed <n>", "std::srand(n) before loading and before the first frame: particles "
                                              "draw from std::rand() (default 1).");
    usage->addCommandLineOption("--play-animations", "Play every osgAnimation animation in the scene from time 0.");
    usage->addCommandLineOption("--progress", "Show the progress bar even when stderr is not a terminal.");
    usage->addCommandLineOption("--retarget-preview <motion>", "Retarget a motion file (BVH, or ASF with its AMC beside "
                                                              "it) onto the first actor and show its own skeleton "
                                                              "playing it beside (docs/retargeting.md).");
}

namespace {

bool readVec3(osg::ArgumentParser& arguments, const std::string& option, osg::Vec3d& value)
{
    return arguments.read(option, value.x(), value.y(), value.z());
}

/** "k/n" with 1 <= k <= n. */
bool parsePart(const std::string& text, unsigned& part, unsigned& numParts)
{
    std::istringstream in(text);
    long k = 0;
    long n = 0;
    char slash = 0;
    if (!(in >> k >> slash >> n) || slash != '/' || !in.eof() || n < 1 || k < 1 || k > n || n > 100000) return false;
    part = unsigned(k);
    numParts = unsigned(n);
    return true;
}

} // namespace

void RenderOptions::getPartFrames(unsigned partIndex, unsigned parts, unsigned& first, unsigned& last) const
{
    const unsigned long count = getNumFrames();
    const unsigned long begin = count * (partIndex - 1) / parts;
    const unsigned long end = count * partIndex / parts; // one past the last
    first = firstFrame + unsigned(begin);
    last = firstFrame + unsigned(end) - 1; // below first when the part is empty
    if (end == begin)
    {
        first = 1;
        last = 0;
    }
}

bool parseRenderOptions(osg::ArgumentParser& arguments, RenderOptions& options, std::string& error)
{
    osgActor::RenderSettings& settings = options.settings;
    while (arguments.read("--size", settings.width, settings.height)) {}
    while (arguments.read("--fov", settings.fovyDegrees)) {}
    while (readVec3(arguments, "--eye", settings.eye)) settings.hasEye = true;
    while (readVec3(arguments, "--center", settings.center)) settings.hasCenter = true;
    while (readVec3(arguments, "--up", settings.up)) {}
    while (arguments.read("--time", options.time)) options.hasTime = true;
    bool hasFrames = false;
    int first = 0;
    int last = 0;
    while (arguments.read("--frames", first, last)) hasFrames = true;
    while (arguments.read("--fps", settings.fps)) {}
    bool hasOutput = false;
    while (arguments.read("-o", options.outputPattern) || arguments.read("--output", options.outputPattern))
        hasOutput = true;
    bool noFrames = false;
    while (arguments.read("--no-frames")) noFrames = true;
    osg::Vec4& bg = settings.background;
    while (arguments.read("--background", bg.r(), bg.g(), bg.b())) bg.a() = 1.0f;
    while (arguments.read("--contact-sheet", options.contactSheet)) {}
    int columns = 0;
    while (arguments.read("--sheet-columns", columns)) {}
    while (arguments.read("--sheet-tile-width", options.sheetTileWidth)) {}
    while (arguments.read("--compare", options.referencePattern)) {}
    while (arguments.read("--tolerance", options.rules.tolerance)) {}
    double allowedPercent = 0.0;
    while (arguments.read("--allowed-share", allowedPercent)) {}
    while (arguments.read("--diff", options.diffPattern)) {}
    while (arguments.read("--compare-sheet", options.compareSheet)) {}
    while (arguments.read("--report", options.reportFile)) {}
    while (arguments.read("--update-references")) options.rules.updateReferences = true;
    while (arguments.read("--check-determinism")) options.checkDeterminism = true;
    int jobs = 1;
    while (arguments.read("--jobs", jobs)) {}
    std::string part;
    while (arguments.read("--part", part)) {}
    int seed = 1;
    while (arguments.read("--seed", seed)) {}
    while (arguments.read("--play-animations")) settings.playAnimations = true;
    while (arguments.read("--progress")) options.forceProgress = true;
    while (arguments.read("--retarget-preview", options.retargetPreview)) {}
    while (arguments.read("--job-report-fd", options.jobReportFd)) {}
    while (arguments.read("--job-scratch", options.jobScratchPattern)) {}
    while (arguments.read("--job-scratch-all")) options.jobScratchAll = true;

    arguments.reportRemainingOptionsAsUnrecognized();
    if (arguments.errors())
    {
        std::ostringstream messages;
        arguments.writeErrorMessages(messages);
        error = messages.str();
        while (!error.empty() && error.back() == '\n') error.pop_back();
        return false;
    }

    for (int pos = 1; pos < arguments.argc(); ++pos)
        if (!arguments.isOption(pos)) options.files.push_back(arguments[pos]);

    // Checks, first the ones a typing slip is most likely to hit.
    if (options.files.empty()) error = "no file to render";
    else if (!settings.validate(error)) error = "--size, --fps, --fov, --eye, --center or --up: " + error;
    else if (hasFrames && options.hasTime) error = "--time and --frames cannot be used together";
    else if (hasFrames && (first < 0 || last < first)) error = "--frames needs 0 <= first <= last";
    else if (!std::isfinite(options.time) || options.time < 0.0)
        error = "--time must be a finite number of seconds from 0 on";
    else if (columns < 0) error = "--sheet-columns cannot be negative";
    else if (options.sheetTileWidth < 1) error = "--sheet-tile-width must be at least 1 pixel";
    else if (noFrames && options.contactSheet.empty() && !options.comparing())
        error = "--no-frames without --contact-sheet or --compare would write nothing";
    else if (options.rules.tolerance < 0 || options.rules.tolerance > 255) error = "--tolerance must lie in 0..255";
    else if (!(allowedPercent >= 0.0 && allowedPercent <= 100.0)) error = "--allowed-share must lie in 0..100 (%)";
    else if (!options.comparing() && (options.rules.updateReferences || !options.diffPattern.empty() ||
                                      !options.compareSheet.empty() || !options.reportFile.empty()))
        error = "--update-references, --diff, --compare-sheet and --report need --compare";
    else if (options.checkDeterminism && (options.comparing() || hasOutput || !options.contactSheet.empty()))
        error = "--check-determinism writes nothing: it cannot be used with --compare, -o or --contact-sheet";
    else if (jobs < 1 || jobs > 1024) error = "--jobs must lie in 1..1024";
    else if (!part.empty() && !parsePart(part, options.part, options.numParts))
        error = "--part needs k/n with 1 <= k <= n, e.g. --part 2/4";
    else if (!part.empty() && jobs > 1) error = "--part and --jobs cannot be used together";
    else if (seed < 0) error = "--seed cannot be negative";
    if (!error.empty()) return false;

    if (hasFrames)
    {
        options.firstFrame = static_cast<unsigned>(first);
        options.lastFrame = static_cast<unsigned>(last);
    }
    // Every part frames the camera where the whole sequence starts.
    settings.framingTime = options.frameTime(options.firstFrame);
    options.writeFrames = !noFrames && (hasOutput || !options.comparing()) && !options.checkDeterminism;
    options.sheetColumns = static_cast<unsigned>(columns);
    options.rules.allowedShare = allowedPercent / 100.0;
    options.jobs = static_cast<unsigned>(jobs);
    settings.seed = static_cast<unsigned>(seed);
    return true;
}

} // namespace osgActorRender
