#include <osgActor/detail/InstancedSkin.h>

#include <osgActor/ActorNode>
#include <osgActor/SkinnedMesh>
#include <osgActor/SkinnedMeshInstance.h>
#include <osgActor/detail/InstancedDraw.h>

#include <typeinfo>

namespace osgActor {
namespace detail {

SkinnedMesh* InstancedSkin::meshOfStep(const ActorCullPlan::Step& step)
{
    if (step.kind != ActorCullPlan::ORDINARY || step.joint != -1 || typeid(*step.node) != typeid(SkinnedMesh))
        return nullptr;
    return static_cast<SkinnedMesh*>(step.node);
}

unsigned InstancedSkin::texelsPerInstance(SkinnedMesh& mesh)
{
    if (!mesh.getSetupError().empty() || !mesh.gpuCanSkin()) return 0;
    const SkinningProgramKey key = programKey(mesh, SkinningProfile::Compatibility);
    // The profiles' bind-pose geometries hold the same arrays and primitives (in other attribute slots).
    const osg::Geometry* geometry = geometryOf(mesh, SkinningProfile::Compatibility);
    if (!geometry || !InstancedDraw::canDraw(*geometry)) return 0;
    return 4 + mesh.getSkin()->getNumJoints() * paletteStride(key);
}

float InstancedSkin::bindScaleOf(const SkinnedMesh& mesh)
{
    // As the ordinary path's palette holds it (SkinPaletteBuffer): the skin's, as a float.
    return mesh.getProgramKey(SkinningProfile::Compatibility).method == SkinningMethod::DualQuaternion
               ? static_cast<float>(mesh.getSkin()->getBindScale())
               : 1.0f;
}

bool InstancedSkin::isInstanceableState(const osg::StateSet* state)
{
    if (!state) return true;
    if (state->getRenderBinMode() != osg::StateSet::INHERIT_RENDERBIN_DETAILS) return false;
    const osg::StateSet::TextureAttributeList& textures = state->getTextureAttributeList();
    return textures.size() <= kSkinPaletteTextureUnit || textures[kSkinPaletteTextureUnit].empty();
}

const SkinnedMeshInstance* InstancedSkin::instanceOf(SkinnedMesh& mesh, ActorNode& actor)
{
    const SkinnedMeshInstance* instance = mesh.instanceFor(actor);
    if (!instance) return nullptr;
    const SkinnedMesh::SkinningPath path = instance->hasOwnPath ? instance->ownPath : mesh.getSkinningPath();
    return path == SkinnedMesh::GPU_SKINNING ? instance : nullptr;
}

bool InstancedSkin::hasMatrices(const SkinnedMeshInstance& instance) { return instance.hasMatrices(); }

const osg::BoundingBox& InstancedSkin::boundOf(const SkinnedMeshInstance& instance) { return instance.getBound(); }

void InstancedSkin::writeInstance(const SkinnedMesh& mesh, const SkinnedMeshInstance& instance,
                                  const osg::Matrixd& modelView, float* out)
{
    const double* m = modelView.ptr();
    for (int k = 0; k < 16; ++k) out[k] = static_cast<float>(m[k]);
    instance.writePaletteRows(programKey(mesh, SkinningProfile::Compatibility), out + 16);
}

SkinningProgramKey InstancedSkin::programKey(const SkinnedMesh& mesh, SkinningProfile profile)
{
    SkinningProgramKey key = mesh.getProgramKey(profile);
    key.instancing = SkinInstancing::PerInstance;
    return key;
}

osg::Geometry* InstancedSkin::geometryOf(SkinnedMesh& mesh, SkinningProfile profile)
{
    return mesh.getBindPoseGeometry(profile);
}

} // namespace detail
} // namespace osgActor
