#include <osgActor/import/RiggedModelFile>

#include <osgActor/import/GltfReader>
#include <osgActor/mocap/MocapImport>

namespace osgActor {

bool isRiggedModelFile(const std::string& path)
{
    const std::string extension = lowerExtensionOf(path);
    return extension == ".gltf" || extension == ".glb";
}

RiggedModelRead readRiggedModelFile(const std::string& path)
{
    if (isRiggedModelFile(path)) return readGltfFile(path);
    RiggedModelRead failed;
    failed.error = path + ": not a rigged model file osgActor reads (expected .gltf or .glb)";
    return failed;
}

} // namespace osgActor
