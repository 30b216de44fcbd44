/* osgActor: the GLSL texts of osgActor/shaders, compiled into the library by CMake (ShaderSources.cpp.in). Internal:
 * SkinningShaders and InstancedActorGroup assemble programs from them. */
#ifndef OSGACTOR_SHADERS_SHADERSOURCES_H
#define OSGACTOR_SHADERS_SHADERSOURCES_H 1

namespace osgActor {
namespace shaders {

extern const char* const kSkinnedMeshVertex;
extern const char* const kSkinnedMeshFragment;
extern const char* const kLightingCompatibility;
extern const char* const kLightingCore;
extern const char* const kInstancedRigidVertex;
extern const char* const kInstancedRigidFragment;
extern const char* const kInstanceData;

} // namespace shaders
} // namespace osgActor

#endif
