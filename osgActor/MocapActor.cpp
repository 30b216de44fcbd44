#include <osgActor/MocapActor>
#include <osgActor/StickFigure>
#include <osgActor/mocap/AmcReader>
#include <osgActor/mocap/BvhReader>

#include <osg/Notify>

#include <algorithm>
#include <cctype>
#include <filesystem>

namespace osgActor {

namespace {

std::string lowerExtension(const std::string& path)
{
    std::string extension = std::filesystem::path(path).extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return extension;
}

MocapImport importFile(const std::string& path, const MocapActorOptions& options)
{
    const std::string extension = lowerExtension(path);
    if (extension == ".bvh")
    {
        BvhImportOptions bvh;
        bvh.scale = options.scale;
        bvh.fileUpAxis = options.fileUpAxis;
        bvh.dropFirstFrame = options.dropFirstFrame;
        bvh.absoluteRootPosition = options.absoluteRootPosition;
        return readBvhFile(path, bvh);
    }
    MocapImport failed;
    if (extension != ".asf")
    {
        failed.error = path + ": not a motion-capture file (expected .bvh or .asf)";
        return failed;
    }
    AsfImportOptions asf;
    asf.scale = options.scale;
    asf.fileUpAxis = options.fileUpAxis;
    asf.frameRate = options.amcFrameRate;
    asf.applyLimits = options.applyAsfLimits;
    const AsfImport skeleton = readAsfFile(path, asf);
    if (!skeleton)
    {
        failed.error = skeleton.error;
        return failed;
    }
    const std::string amc = options.amcFile.empty() ? findAmcBeside(path) : options.amcFile;
    if (amc.empty())
    {
        failed.error = path + ": no AMC motion given and none found beside it";
        return failed;
    }
    return readAmcFile(amc, skeleton);
}

} // namespace

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
        if (name.size() > base.size() && name.compare(0, base.size(), base) == 0 && lowerExtension(name) == ".amc")
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
        // Pose the first frame at once, so bounds and queries are right before the first update.
        actor->runControllers(0.0);
        actor->updatePose();
    }
    if (options.addFigure) addStickFigure(*actor);
    return actor;
}

} // namespace osgActor
