#include <osgActor/import/RiggedModelFile>

#include <osgActor/import/AssimpReader>
#include <osgActor/import/GltfReader>
#include <osgActor/mocap/MocapImport>

#include <map>

namespace osgActor {

namespace {

/** The readers added by other layers, by extension. */
std::map<std::string, RiggedModelFileReader>& addedReaders()
{
    static std::map<std::string, RiggedModelFileReader> readers;
    return readers;
}

bool isGltfFile(const std::string& extension) { return extension == ".gltf" || extension == ".glb"; }

} // namespace

void addRiggedModelFileReader(const std::string& extension, RiggedModelFileReader reader)
{
    addedReaders()[extension] = reader;
}

bool isRiggedModelFile(const std::string& path)
{
    const std::string extension = lowerExtensionOf(path);
    return isGltfFile(extension) || isAssimpModelFile(path) || addedReaders().count(extension) > 0;
}

RiggedModelRead readRiggedModelFile(const std::string& path)
{
    const std::string extension = lowerExtensionOf(path);
    if (isGltfFile(extension)) return readGltfFile(path);
    if (isAssimpModelFile(path)) return readAssimpFile(path);
    const auto added = addedReaders().find(extension);
    if (added != addedReaders().end() && added->second) return added->second(path);
    RiggedModelRead failed;
    failed.error = path + ": not a rigged model file osgActor reads (expected .gltf, .glb, .dae, .fbx, .x, .osgt, ...)";
    return failed;
}

} // namespace osgActor
