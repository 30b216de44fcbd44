# The rigged-model import (docs/import.md): readers (glTF through tinygltf) into the format-neutral RiggedModel, and
# its mapping onto an actor. No OSG (GLM and tinygltf only); included by osgActor/CMakeLists.txt, which compiles it
# into the object library osgActorImport, part of libosgActor. Paths are relative to osgActor/.

set(OSGACTOR_IMPORT_HEADERS
    import/ChannelSampling
    import/EulerFit
    import/GltfReader
    import/RiggedActorBuilder
    import/RiggedModel
    import/RiggedModelFile
    import/RiggedMotionFile
    import/UniformClip)
set(OSGACTOR_IMPORT_SOURCES
    import/ChannelSampling.cpp
    import/EulerFit.cpp
    import/GltfAccessors
    import/GltfAccessors.cpp
    import/GltfReader.cpp
    import/RiggedActorBuilder.cpp
    import/RiggedModel.cpp
    import/RiggedModelFile.cpp
    import/RiggedMotionFile.cpp
    import/UniformClip.cpp)
