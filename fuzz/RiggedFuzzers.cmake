# The rigged-model import's fuzzers (docs/import.md): fuzz_gltf (the glTF reader on arbitrary bytes) and fuzz_rigged
# (the Assimp reader's conversion of aiScenes built from arbitrary bytes), each with the mapping onto an actor. They
# compile the import's objects (osgActorImport, OSG-free) with the core's.
foreach(_target fuzz_gltf fuzz_rigged)
    osgactor_add_fuzzer(${_target} ${_target}.cpp)
    target_sources(${_target} PRIVATE $<TARGET_OBJECTS:osgActorImport>)
    target_link_libraries(${_target} PRIVATE TinyGLTF::TinyGLTF assimp::assimp)
endforeach()
