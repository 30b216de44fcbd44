# The rigged-model import (docs/import.md): readers (glTF through tinygltf; Collada, FBX, DirectX and Assimp's other
# skeletal formats through Assimp) into the format-neutral RiggedModel, and its mapping onto an actor. No OSG (GLM,
# tinygltf and Assimp only); included by osgActor/CMakeLists.txt, which compiles it
# into the object library osgActorImport, part of libosgActor. Paths are relative to osgActor/.

set(OSGACTOR_IMPORT_HEADERS
    import/AssimpReader
    import/ChannelSampling
    import/EulerFit
    import/GltfReader
    import/RiggedActorBuilder
    import/RiggedModel
    import/RiggedModelFile
    import/RiggedMotionFile
    import/UniformClip)
set(OSGACTOR_IMPORT_SOURCES
    import/AssimpAnimations.cpp
    import/AssimpMaterials.cpp
    import/AssimpMeshes.cpp
    import/AssimpReader.cpp
    import/AssimpScene
    import/ChannelSampling.cpp
    import/EulerFit.cpp
    import/GltfAccessors
    import/GltfAccessors.cpp
    import/GltfReader.cpp
    import/ImageDecoding
    import/ImageDecoding.cpp
    import/RiggedActorBuilder.cpp
    import/RiggedModel.cpp
    import/RiggedModelFile.cpp
    import/RiggedMotionFile.cpp
    import/UniformClip.cpp)
