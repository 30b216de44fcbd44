// libFuzzer target: the glTF reader (through tinygltf, from memory) and the mapping onto an actor, on arbitrary
// bytes (fuzz/RiggedContract says what they must do).
#include "FuzzMain"
#include "RiggedContract"

#include <osgActor/import/GltfReader>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    const osgActor::RiggedModelRead read = osgActor::readGltfMemory(data, size, "input.gltf");
    osgActor::fuzz::require(osgActor::contract::checkRiggedRead(read, "input.gltf"));
    return 0;
}
