#include <osgActor/MocapActor>
#include <osgActor/StickFigure>
#include <osgActor/mocap/MotionFile>
#include <osgActor/text/Numbers>

#include <osg/Notify>

#include <algorithm>
#include <filesystem>
#include <sstream>

namespace osgActor {

namespace {

/** Reads a BVH file, or an ASF skeleton with its AMC motion (named in the options or found beside it). */
MocapImport importFile(const std::string& path, const MocapActorOptions& options)
{
    MotionFileOptions motion;
    static_cast<MotionImportOptions&>(motion) = options;
    const std::string extension = lowerExtensionOf(path);
    if (extension == ".bvh") return readMotionFile(path, motion);
    MocapImport failed;
    if (extension != ".asf")
    {
        failed.error = path + ": not a motion-capture file (expected .bvh or .asf)";
        return failed;
    }
    motion.skeletonFile = path;
    const std::string amc = options.amcFile.empty() ? findAmcBeside(path) : options.amcFile;
    if (amc.empty())
    {
        failed.error = path + ": no AMC motion given and none found beside it";
        return failed;
    }
    return readMotionFile(amc, motion);
}

} // namespace

bool parseMocapOptionString(const std::string& text, MocapActorOptions& options, std::string& error)
{
    std::istringstream words(text);
    std::string word;
    while (words >> word)
    {
        const std::size_t equals = word.find('=');
        const std::string key = word.substr(0, equals);
        std::string value = equals == std::string::npos ? std::string() : word.substr(equals + 1);
        auto positive = [&](double& into) {
            double number = 0.0;
            if (!parseNumber(value, number) || !(number > 0.0))
            {
                error = "option " + key + " needs a positive number, not '" + value + "'";
                return false;
            }
            into = number;
            return true;
        };
        auto bad = [&](const char* expected) {
            error = "option " + key + " must be " + expected + ", not '" + value + "'";
            return false;
        };
        // Words of earlier versions, still read: the options now use the .actor format's words.
        auto deprecated = [&](const char* old, const char* now) {
            if (value != old) return;
            OSG_NOTICE << "osgActor: option " << key << "=" << old << " is deprecated; write " << key << "=" << now
                       << std::endl;
            value = now;
        };
        if (key == "amc") options.amcFile = value;
        else if (key == "scale") { if (!positive(options.scale)) return false; }
        else if (key == "fps") { if (!positive(options.amcFrameRate)) return false; }
        else if (key == "up")
        {
            deprecated("Y", "y");
            deprecated("Z", "z");
            if (!parseUpAxis(value, options.fileUpAxis)) return bad("y or z");
        }
        else if (key == "mode")
        {
            if (!parsePlayMode(value, options.playMode)) return bad("once, loop or pingpong");
        }
        else if (key == "rootMotion")
        {
            deprecated("skeleton", "in_skeleton");
            deprecated("transforms", "to_transforms");
            deprecated("inplace", "in_place");
            if (!parseRootMotion(value, options.rootMotion)) return bad("in_skeleton, to_transforms or in_place");
        }
        else if (word == "dropFirstFrame") options.dropFirstFrame = true;
        else if (word == "absoluteRoot") options.absoluteRootPosition = true;
        else if (word == "limits") options.applyAsfLimits = true;
        else if (word == "noFigure") options.addFigure = false;
        // anything else belongs to another plugin
    }
    return true;
}

std::string findAmcBeside(const std::string& asfPath)
{
    namespace fs = std::filesystem;
    const fs::path asf(asfPath);
    const std::string base = asf.stem().string();
    const fs::path folder = asf.has_parent_path() ? asf.parent_path() : fs::path(".");
    std::error_code ec;
    if (fs::exists(folder / (base + ".amc"), ec)) return (folder / (base + ".amc")).string();
    std::vector<std::string> candidates;
    for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec))
    {
        const std::string name = it->path().filename().string();
        if (name.size() > base.size() && name.compare(0, base.size(), base) == 0 && lowerExtensionOf(name) == ".amc")
            candidates.push_back(it->path().string());
    }
    std::sort(candidates.begin(), candidates.end());
    return candidates.empty() ? std::string() : candidates.front();
}

osg::ref_ptr<ActorNode> readMocapActor(const std::string& path, const MocapActorOptions& options, std::string& error)
{
    const MocapImport imported = importFile(path, options);
    if (!imported)
    {
        error = imported.error;
        return nullptr;
    }
    for (const std::string& warning : imported.warnings) OSG_WARN << "osgActor: " << warning << std::endl;

    osg::ref_ptr<ActorNode> actor = new ActorNode(imported.definition);
    actor->setName(imported.definition->getName());
    if (imported.clip)
    {
        ClipLibraryPtr library = std::make_shared<ClipLibrary>();
        library->addClip(imported.clip);
        actor->setClipLibrary(library);
        auto player = std::make_shared<ClipPlayer>(imported.clip);
        player->setName("mocap");
        player->setPlayMode(options.playMode);
        player->setRootMotion(options.rootMotion);
        actor->addController(player);
        // Pose the first frame at once, so bounds and queries are right before the first update. (Not by running
        // the controllers: their clock starts at the first frame stamp the actor sees, whenever that is.)
        const double* first = imported.clip->getFrame(0);
        actor->setDofs(std::vector<double>(first, first + imported.clip->getNumChannels()));
        actor->updatePose();
    }
    if (options.addFigure) addStickFigure(*actor);
    return actor;
}

} // namespace osgActor
