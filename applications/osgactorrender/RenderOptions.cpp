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
                          "through OSMesa, with no display.");
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
                                "Output PNG file pattern, %04d is the frame number (default frame_%04d.png).");
    usage->addCommandLineOption("--no-frames", "Write no frame images (with --contact-sheet: the sheet only).");
    usage->addCommandLineOption("--background <r> <g> <b>", "Background colour, 0..1 (default 0.2 0.2 0.4).");
    usage->addCommandLineOption("--contact-sheet <file>", "Also write every frame, reduced, into one image.");
    usage->addCommandLineOption("--sheet-columns <n>", "Columns of the contact sheet (default: a square grid).");
    usage->addCommandLineOption("--sheet-tile-width <pixels>", "Width of a frame on the contact sheet (default 160).");
    usage->addCommandLineOption("--progress", "Show the progress bar even when stderr is not a terminal.");
    usage->addCommandLineOption("--retarget-preview <motion>", "Retarget a motion file (BVH, or ASF with its AMC beside "
                                                              "it) onto the first actor and show its own skeleton "
                                                              "playing it beside (docs/retargeting.md).");
}

namespace {

// OSMesa's largest viewport (SWRAST_MAX_WIDTH/HEIGHT in Mesa); larger buffers would only waste memory.
const int kMaxImageSize = 16384;
// The most update steps from time 0 to the last frame (about 9 hours of simulation at 30 frames per second).
const double kMaxSteps = 1e6;

bool readVec3(osg::ArgumentParser& arguments, const std::string& option, osg::Vec3d& value)
{
    return arguments.read(option, value.x(), value.y(), value.z());
}

} // namespace

bool parseRenderOptions(osg::ArgumentParser& arguments, RenderOptions& options, std::string& error)
{
    while (arguments.read("--size", options.width, options.height)) {}
    while (arguments.read("--fov", options.fovyDegrees)) {}
    while (readVec3(arguments, "--eye", options.view.eye)) options.hasEye = true;
    while (readVec3(arguments, "--center", options.view.center)) options.hasCenter = true;
    while (readVec3(arguments, "--up", options.view.up)) {}
    while (arguments.read("--time", options.time)) options.hasTime = true;
    bool hasFrames = false;
    int first = 0;
    int last = 0;
    while (arguments.read("--frames", first, last)) hasFrames = true;
    while (arguments.read("--fps", options.fps)) {}
    while (arguments.read("-o", options.outputPattern) || arguments.read("--output", options.outputPattern)) {}
    while (arguments.read("--no-frames")) options.writeFrames = false;
    osg::Vec4& bg = options.background;
    while (arguments.read("--background", bg.r(), bg.g(), bg.b())) bg.a() = 1.0f;
    while (arguments.read("--contact-sheet", options.contactSheet)) {}
    int columns = 0;
    while (arguments.read("--sheet-columns", columns)) {}
    while (arguments.read("--sheet-tile-width", options.sheetTileWidth)) {}
    while (arguments.read("--progress")) options.forceProgress = true;
    while (arguments.read("--retarget-preview", options.retargetPreview)) {}

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
    else if (options.width < 1 || options.height < 1 || options.width > kMaxImageSize || options.height > kMaxImageSize)
        error = "--size needs a width and height from 1 to " + std::to_string(kMaxImageSize) + " pixels";
    else if (!(options.fovyDegrees > 0.0 && options.fovyDegrees < 180.0)) error = "--fov must lie in (0, 180) degrees";
    else if (hasFrames && options.hasTime) error = "--time and --frames cannot be used together";
    else if (hasFrames && (first < 0 || last < first)) error = "--frames needs 0 <= first <= last";
    else if (!(options.fps > 0.0) || !std::isfinite(options.fps)) error = "--fps must be a positive rate";
    else if (!std::isfinite(options.time)) error = "--time must be a finite number of seconds";
    else if (options.time * options.fps > kMaxSteps || (hasFrames && last > kMaxSteps))
        error = "the scene is updated at every frame from time 0: more than " + std::to_string(int(kMaxSteps)) +
                " frames (--time x --fps, or --frames) is too many";
    else if (columns < 0) error = "--sheet-columns cannot be negative";
    else if (options.sheetTileWidth < 1) error = "--sheet-tile-width must be at least 1 pixel";
    else if (options.view.up.length2() == 0.0) error = "--up cannot be the zero vector";
    else if (options.hasEye && options.hasCenter && options.view.eye == options.view.center)
        error = "--eye and --center cannot be the same point";
    else if (!options.writeFrames && options.contactSheet.empty())
        error = "--no-frames without --contact-sheet would write nothing";
    if (!error.empty()) return false;

    if (hasFrames)
    {
        options.firstFrame = static_cast<unsigned>(first);
        options.lastFrame = static_cast<unsigned>(last);
    }
    options.sheetColumns = static_cast<unsigned>(columns);
    return true;
}

} // namespace osgActorRender
