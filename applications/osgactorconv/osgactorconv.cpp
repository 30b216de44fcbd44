/* osgactorconv: converts motion capture (BVH, ASF+AMC), retargets it onto an actor, and dumps joint positions so
 * other tools can check the import. Exit status 0 on success, 1 on bad input (with file:line on stderr), 2 on bad
 * usage. */
#include "RetargetConversion.h"
#include "RiggedModelDump"

#include <osgActor/import/RiggedModelFile>
#include <osgActor/io/ActorDocument>
#include <osgActor/io/ActorWriter>
#include <osgActor/mocap/AmcReader>
#include <osgActor/mocap/AsfReader>
#include <osgActor/mocap/BvhReader>
#include <osgActor/mocap/BvhWriter>
#include <osgActor/mocap/MotionFile>
#include <osgActor/mocap/PositionsCsv>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <limits>
#include <string>
#include <vector>

using namespace osgActor;

namespace {

const char* const kUsage =
    "usage: osgactorconv [options] INPUT.bvh\n"
    "       osgactorconv [options] INPUT.asf [MOTION.amc]\n"
    "       osgactorconv --dump-positions|--dump-skinned FILE [--clip NAME] [--fps N] INPUT.gltf|INPUT.glb\n"
    "\n"
    "Reads motion capture into an osgActor actor and clip, then writes it out or dumps joint positions.\n"
    "\n"
    "  --dump-positions   print CSV 'frame,joint,x,y,z' to stdout (or -o), one row per joint per frame: the\n"
    "                     world position of each joint's origin (BVH: each ROOT/JOINT; ASF/AMC: 'root' and the\n"
    "                     start of each bone), in the file's own axes and units (no scale, no axis change),\n"
    "                     frames numbered from 0 at the first frame of data\n"
    "  --frames A:B       only frames A (included) to B (excluded); 'A:' and ':B' leave an end open\n"
    "  -o, --output FILE  write to FILE: .actor writes the actor (turned Z-up, scaled) with its motion as a\n"
    "                     'clip' section; .bvh exports BVH (the file's own axes and units, so it reads back\n"
    "                     the same)\n"
    "  --amc FILE         the AMC motion of an ASF skeleton (or give it after the ASF)\n"
    "  --fps N            frame rate of AMC motion (default 120, CMU's); glTF: rows at times k / N from the\n"
    "                     clip's first key to its last inclusive (default 30), joints named by node (or node<i>)\n"
    "  --clip NAME        glTF: the animation to dump (default the first)\n"
    "  --dump-skinned FILE glTF: write CSV 'frame,mesh,vertex,x,y,z' of the CPU-skinned primitives (mesh: index\n"
    "                     in meshes[] then primitives[] order) at the same times, in the file's axes and units\n"
    "  --scale S          multiply lengths by S when converting to .actor (not for --dump-positions)\n"
    "  --up Y|Z           the input's up axis for .actor output (default Y; .actor is Z-up like OSG)\n"
    "  --drop-first-frame drop frame 0 (the reference pose of CMU BVH conversions) when converting\n"
    "  --absolute-root    BVH root positions are absolute (3ds Max), not added to the root OFFSET\n"
    "  --link-motion      .actor output: the clip names the motion file (and an AMC's skeleton), by paths\n"
    "                     relative to the output's folder, with the options above, instead of holding\n"
    "                     its frames; the actor reads the motion when it is loaded\n"
    "  --retarget TARGET.actor\n"
    "                     retarget the motion onto that actor (its joint names, rest pose and proportions)\n"
    "                     and write its .actor file with the motion as a clip: to -o, or TARGET.actor itself\n"
    "  --map FILE         with --retarget: the joint map of the input's skeleton (default: guessed)\n"
    "  --no-ik            with --retarget: no IK pass (feet not planted, hands and feet not placed)\n"
    "  -h, --help         this text\n";

struct Arguments
{
    std::vector<std::string> inputs;
    std::string amc;
    std::string output;
    bool dumpPositions = false;
    unsigned firstFrame = 0;
    unsigned endFrame = std::numeric_limits<unsigned>::max();
    double fps = 120.0;
    double scale = 1.0;
    bool dropFirstFrame = false;
    bool absoluteRoot = false;
    bool linkMotion = false;
    UpAxis up = UpAxis::Y;
    bool fpsGiven = false;
    std::string clip;
    std::string dumpSkinned;
    RetargetConversion retarget;
};

bool endsWith(std::string text, const std::string& suffix)
{
    std::transform(text.begin(), text.end(), text.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return text.size() >= suffix.size() && text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0;
}

bool parseUnsigned(const std::string& text, unsigned& value)
{
    if (text.empty() || text.find_first_not_of("0123456789") != std::string::npos || text.size() > 9) return false;
    value = static_cast<unsigned>(std::stoul(text));
    return true;
}

bool parsePositive(const std::string& text, double& value)
{
    char* end = nullptr;
    value = std::strtod(text.c_str(), &end);
    return !text.empty() && *end == '\0' && value > 0.0 && value < std::numeric_limits<double>::infinity();
}

/** Parses the command line; returns an error message, empty on success. */
std::string parseArguments(int argc, char** argv, Arguments& args, bool& help)
{
    for (int i = 1; i < argc; ++i)
    {
        const std::string arg = argv[i];
        auto value = [&](std::string& into) {
            if (i + 1 >= argc) return false;
            into = argv[++i];
            return true;
        };
        std::string text;
        if (arg == "-h" || arg == "--help") help = true;
        else if (arg == "--dump-positions") args.dumpPositions = true;
        else if (arg == "--drop-first-frame") args.dropFirstFrame = true;
        else if (arg == "--absolute-root") args.absoluteRoot = true;
        else if (arg == "--link-motion") args.linkMotion = true;
        else if (arg == "--no-ik") args.retarget.ik = false;
        else if (arg == "--retarget" || arg == "--map")
        {
            if (!value(arg == "--map" ? args.retarget.mapFile : args.retarget.targetFile))
                return arg + " needs a file name";
        }
        else if (arg == "-o" || arg == "--output")
        {
            if (!value(args.output)) return arg + " needs a file name";
        }
        else if (arg == "--clip")
        {
            if (!value(args.clip)) return "--clip needs an animation name";
        }
        else if (arg == "--dump-skinned")
        {
            if (!value(args.dumpSkinned)) return "--dump-skinned needs a file name";
        }
        else if (arg == "--amc")
        {
            if (!value(args.amc)) return "--amc needs a file name";
        }
        else if (arg == "--fps")
        {
            if (!value(text) || !parsePositive(text, args.fps)) return "--fps needs a positive number";
            args.fpsGiven = true;
        }
        else if (arg == "--scale")
        {
            if (!value(text) || !parsePositive(text, args.scale)) return "--scale needs a positive number";
        }
        else if (arg == "--up")
        {
            if (!value(text) || (text != "Y" && text != "y" && text != "Z" && text != "z")) return "--up needs Y or Z";
            args.up = text == "Y" || text == "y" ? UpAxis::Y : UpAxis::Z;
        }
        else if (arg == "--frames")
        {
            const std::size_t colon = value(text) ? text.find(':') : std::string::npos;
            if (colon == std::string::npos) return "--frames needs A:B";
            const std::string a = text.substr(0, colon), b = text.substr(colon + 1);
            if ((!a.empty() && !parseUnsigned(a, args.firstFrame)) || (!b.empty() && !parseUnsigned(b, args.endFrame)))
                return "--frames needs whole numbers, as in 10:20";
        }
        else if (!arg.empty() && arg[0] == '-') return "unknown option " + arg;
        else args.inputs.push_back(arg);
    }
    if (help) return std::string();
    if (args.inputs.empty() || args.inputs.size() > 2) return "give one input file (and an AMC after an ASF)";
    if (args.inputs.size() == 2) args.amc = args.inputs[1];
    if (!args.retarget.targetFile.empty())
    {
        if (args.dumpPositions || args.linkMotion || !args.dumpSkinned.empty())
            return "--retarget writes a .actor file: no --dump-positions, --dump-skinned or --link-motion";
        if (isRiggedModelFile(args.inputs[0])) return "--retarget reads motion capture (.bvh, .asf with .amc)";
        if (!args.output.empty() && !endsWith(args.output, ".actor")) return "--retarget writes a .actor file";
        args.retarget.outputFile = args.output;
        return std::string();
    }
    if (!args.retarget.mapFile.empty()) return "--map is for --retarget";
    if (!args.dumpSkinned.empty() && !isRiggedModelFile(args.inputs[0])) return "--dump-skinned is for .gltf/.glb input";
    if (!args.dumpPositions && args.output.empty() && args.dumpSkinned.empty())
        return "nothing to do: give --dump-positions or -o FILE";
    if (args.linkMotion && (args.dumpPositions || !endsWith(args.output, ".actor")))
        return "--link-motion is for .actor output";
    return std::string();
}

/** Reads the input; dump selects the file's own frame and units (no scale, no axis change, no limits); toActor
  * turns it Z-up and scales it, as an actor in OSG is. */
MocapImport readInput(const Arguments& args, bool dump, bool toActor)
{
    const std::string& input = args.inputs[0];
    if (endsWith(input, ".bvh"))
    {
        BvhImportOptions options;
        options.convertToZUp = toActor; // BVH output and the dump stay in the file's frame
        options.fileUpAxis = args.up;
        options.endSitesAsJoints = !dump;
        options.absoluteRootPosition = args.absoluteRoot;
        options.scale = toActor ? args.scale : 1.0;
        options.dropFirstFrame = !dump && args.dropFirstFrame;
        return readBvhFile(input, options);
    }
    if (endsWith(input, ".asf"))
    {
        AsfImportOptions options;
        options.convertToZUp = toActor;
        options.fileUpAxis = args.up;
        options.applyLimits = !dump;
        options.frameRate = args.fps;
        options.scale = toActor ? args.scale : 1.0;
        const AsfImport skeleton = readAsfFile(input, options);
        MocapImport failed;
        if (!skeleton)
        {
            failed.error = skeleton.error;
            return failed;
        }
        if (args.amc.empty())
        {
            failed.definition = skeleton.definition; // a skeleton without motion
            return failed;
        }
        return readAmcFile(args.amc, skeleton);
    }
    MocapImport failed;
    failed.error = input + ": unknown input format (expected .bvh or .asf)";
    return failed;
}

/** The imported motion as frames in the .actor file, played in a loop. */
ClipDocument embeddedClip(const MocapImport& imported)
{
    ClipDocument clip;
    clip.clip = imported.clip;
    clip.play = true;
    return clip;
}

/** path as the .actor file at output will name it, with forward slashes: relative to the output's folder, so the
  * two can move together, unless they share no folder but the root (then absolute). */
std::string pathFromOutput(const std::string& path, const std::string& output)
{
    namespace fs = std::filesystem;
    const fs::path file = fs::absolute(path).lexically_normal();
    const fs::path folder = fs::absolute(output).parent_path().lexically_normal();
    const auto firstFolder = [](const fs::path& p) {
        return std::next(p.begin()) != p.end() ? *std::next(p.begin()) : fs::path();
    };
    if (firstFolder(file) != firstFolder(folder)) return file.generic_string();
    return file.lexically_relative(folder).generic_string();
}

/** A clip that names the motion file (and an AMC's skeleton) with the options it was converted with, played in a
  * loop: the .actor file reads the very same motion when it is loaded (docs/actor-format.md, "file"). */
ClipDocument linkedClip(const Arguments& args, const std::string& clipName)
{
    const bool bvh = endsWith(args.inputs[0], ".bvh");
    ClipDocument clip;
    clip.play = true;
    clip.file = pathFromOutput(bvh ? args.inputs[0] : args.amc, args.output);
    MotionFileOptions& options = clip.fileOptions;
    options.name = clipName;
    options.scale = args.scale;
    options.fileUpAxis = args.up;
    if (bvh)
    {
        options.dropFirstFrame = args.dropFirstFrame;
        options.absoluteRootPosition = args.absoluteRoot;
    }
    else
    {
        options.skeletonFile = pathFromOutput(args.inputs[0], args.output);
        options.amcFrameRate = args.fps;
    }
    return clip;
}

} // namespace

int main(int argc, char** argv)
{
    Arguments args;
    bool help = false;
    const std::string usageError = parseArguments(argc, argv, args, help);
    if (help)
    {
        std::cout << kUsage;
        return 0;
    }
    if (!usageError.empty())
    {
        std::cerr << "osgactorconv: " << usageError << "\n\n" << kUsage;
        return 2;
    }

    if (isRiggedModelFile(args.inputs[0]))
    {
        if (!args.dumpPositions && !args.output.empty())
        {
            std::cerr << "osgactorconv: glTF input is dumped (--dump-positions, --dump-skinned), not converted\n";
            return 2;
        }
        std::ofstream file;
        if (args.dumpPositions && !args.output.empty()) file.open(args.output, std::ios::binary);
        if (args.dumpPositions && !args.output.empty() && !file)
        {
            std::cerr << "osgactorconv: " << args.output << ": cannot write the file\n";
            return 1;
        }
        RiggedModelDumpRequest request;
        request.input = args.inputs[0];
        request.clip = args.clip;
        request.fps = args.fpsGiven ? args.fps : 30.0;
        request.positions = args.dumpPositions ? (args.output.empty() ? &std::cout : &file) : nullptr;
        request.skinnedPath = args.dumpSkinned;
        return runRiggedModelDump(request, std::cerr);
    }

    const bool retargeting = !args.retarget.targetFile.empty();
    const bool toActor = !args.dumpPositions && (retargeting || endsWith(args.output, ".actor"));
    const MocapImport imported = readInput(args, args.dumpPositions, toActor);
    if (!imported)
    {
        std::cerr << "osgactorconv: " << imported.error << "\n";
        return 1;
    }
    for (const std::string& warning : imported.warnings) std::cerr << "osgactorconv: warning: " << warning << "\n";
    if (retargeting) return retargetIntoActorFile(args.retarget, imported);

    std::ofstream file;
    if (!args.output.empty())
    {
        if (!args.dumpPositions && !toActor && !endsWith(args.output, ".bvh"))
        {
            std::cerr << "osgactorconv: " << args.output << ": unknown output format (expected .actor or .bvh)\n";
            return 2;
        }
        file.open(args.output, std::ios::binary);
        if (!file)
        {
            std::cerr << "osgactorconv: " << args.output << ": cannot write the file\n";
            return 1;
        }
    }
    std::ostream& out = args.output.empty() ? std::cout : file;
    std::string error;
    bool written = false;
    if (args.dumpPositions)
    {
        if (!imported.clip) error = args.inputs[0] + ": the input holds no motion to dump";
        else written = writePositionsCsv(out, imported.definition, *imported.clip, args.firstFrame, args.endFrame,
                                         error);
    }
    else if (toActor)
    {
        ActorDocument document = makeDocument(*imported.definition);
        document.name = imported.definition->getName();
        if (imported.clip) // the motion, played in a loop when the file is loaded
            document.clips.push_back(args.linkMotion ? linkedClip(args, imported.clip->getName()) : embeddedClip(imported));
        writeActor(out, document);
        written = static_cast<bool>(out);
        if (!written) error = args.output + ": cannot write the file";
    }
    else
        written = writeBvh(out, *imported.definition, imported.clip.get(), error);
    if (!written)
    {
        std::cerr << "osgactorconv: " << error << "\n";
        return 1;
    }
    return 0;
}
