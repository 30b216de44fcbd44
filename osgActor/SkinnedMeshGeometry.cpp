#include "SkinnedMeshGeometry.h"

#include <osg/BufferObject>

#include <sstream>

namespace osgActor {

namespace {

/** Every per-vertex array of the surface, with where it sits (for messages). */
template <class Function>
void forEachSurfaceArray(const osg::Geometry& surface, Function f)
{
    if (surface.getColorArray()) f(surface.getColorArray(), std::string("its colour array"));
    if (surface.getSecondaryColorArray()) f(surface.getSecondaryColorArray(), std::string("its secondary colours"));
    if (surface.getFogCoordArray()) f(surface.getFogCoordArray(), std::string("its fog coordinates"));
    for (unsigned i = 0; i < surface.getNumTexCoordArrays(); ++i)
        if (surface.getTexCoordArray(i)) f(surface.getTexCoordArray(i), "texture coordinates " + std::to_string(i));
}

} // namespace

unsigned shaderInfluences(const Skin& skin)
{
    const SkinVertices vertices = skin.getVertices();
    for (unsigned k = 4; k < kMaxSkinInfluences; ++k)
        if (vertices.counts[k] > 0) return 8;
    return 4;
}

std::string checkSkinnedSurface(const Skin& skin, const osg::Geometry& surface)
{
    const unsigned numVertices = skin.getNumVertices();
    std::ostringstream why;
    if (surface.getVertexArray() || surface.getNormalArray())
        return "the surface has its own vertex or normal array; the skin's are drawn";
    forEachSurfaceArray(surface, [&](const osg::Array* array, const std::string& name) {
        if (why.tellp() == 0 && array->getBinding() == osg::Array::BIND_PER_VERTEX &&
            array->getNumElements() != numVertices)
            why << "the surface's " << name << " has " << array->getNumElements() << " entries for "
                << numVertices << " vertices";
    });
    if (why.tellp() > 0) return why.str();
    for (unsigned unit = 5; unit < surface.getNumTexCoordArrays(); ++unit)
        if (surface.getTexCoordArray(unit))
            return "the surface has texture coordinates " + std::to_string(unit) +
                   "; units 5-7 alias the joint and weight attributes in the core profile (skinAttributeSlots())";
    for (unsigned p = 0; p < surface.getNumPrimitiveSets(); ++p)
    {
        const osg::PrimitiveSet* primitives = surface.getPrimitiveSet(p);
        for (unsigned i = 0; i < primitives->getNumIndices(); ++i)
            if (primitives->index(i) >= numVertices)
            {
                why << "primitive set " << p << " names vertex " << primitives->index(i) << " at position " << i
                    << "; the skin has " << numVertices;
                return why.str();
            }
    }
    return std::string();
}

SkinVertexArrays makeSkinVertexArrays(const Skin& skin)
{
    const unsigned numVertices = skin.getNumVertices();
    const bool eight = shaderInfluences(skin) == 8;
    SkinVertexArrays arrays;
    arrays.positions = new osg::Vec3Array(numVertices);
    arrays.joints = new osg::Vec4Array(numVertices);
    arrays.weights = new osg::Vec4Array(numVertices);
    if (eight) arrays.weights1 = new osg::Vec4Array(numVertices);
    for (unsigned v = 0; v < numVertices; ++v)
    {
        const glm::vec3& p = skin.getBindPosition(v);
        (*arrays.positions)[v].set(p.x, p.y, p.z);
        float joints[kMaxSkinInfluences] = {};
        float weights[kMaxSkinInfluences] = {};
        const unsigned count = skin.getNumInfluences(v);
        for (unsigned k = 0; k < count; ++k)
        {
            joints[k] = skin.getInfluenceJoints(v)[k];
            weights[k] = skin.getInfluenceWeights(v)[k];
        }
        for (unsigned c = 0; c < 4; ++c)
        {
            (*arrays.joints)[v][c] = eight ? joints[c] + 4096.0f * joints[c + 4] : joints[c];
            (*arrays.weights)[v][c] = weights[c];
            if (eight) (*arrays.weights1)[v][c] = weights[c + 4];
        }
    }
    if (skin.hasNormals())
    {
        // The skin keeps its vertices grouped by influence count; outputIndices gives each one's place in the file.
        const SkinVertices vertices = skin.getVertices();
        arrays.normals = new osg::Vec3Array(numVertices);
        for (std::size_t i = 0; i < vertices.size(); ++i)
        {
            const glm::vec3& n = vertices.normals[i];
            (*arrays.normals)[vertices.outputIndices[i]].set(n.x, n.y, n.z);
        }
    }
    osg::ref_ptr<osg::VertexBufferObject> buffer = new osg::VertexBufferObject;
    for (osg::Array* array : {static_cast<osg::Array*>(arrays.positions.get()), static_cast<osg::Array*>(arrays.normals.get()),
                              static_cast<osg::Array*>(arrays.joints.get()), static_cast<osg::Array*>(arrays.weights.get()),
                              static_cast<osg::Array*>(arrays.weights1.get())})
        if (array) array->setBufferObject(buffer.get());
    return arrays;
}

osg::ref_ptr<osg::Geometry> makeBindPoseGeometry(const SkinVertexArrays& arrays, const osg::Geometry& surface,
                                                 SkinningProfile profile)
{
    osg::ref_ptr<osg::Geometry> geometry = new osg::Geometry;
    geometry->setName(surface.getName());
    geometry->setUseDisplayList(false);
    // SkinnedMesh culls against the actor's bound itself; this geometry's own box is the bind pose's.
    geometry->setCullingActive(false);
    geometry->setVertexArray(arrays.positions.get());
    if (arrays.normals) geometry->setNormalArray(arrays.normals.get(), osg::Array::BIND_PER_VERTEX);
    if (surface.getColorArray()) geometry->setColorArray(const_cast<osg::Array*>(surface.getColorArray()));
    geometry->setTexCoordArrayList(surface.getTexCoordArrayList());
    const SkinAttributeSlots slots = skinAttributeSlots(profile);
    geometry->setVertexAttribArray(slots.joints, arrays.joints.get(), osg::Array::BIND_PER_VERTEX);
    geometry->setVertexAttribArray(slots.weights, arrays.weights.get(), osg::Array::BIND_PER_VERTEX);
    if (arrays.weights1) geometry->setVertexAttribArray(slots.weights1, arrays.weights1.get(), osg::Array::BIND_PER_VERTEX);
    geometry->setPrimitiveSetList(surface.getPrimitiveSetList());
    // Puts the surface's arrays that have no buffer object yet in the skin's (the first array's), and gives the
    // primitive sets an element buffer object.
    geometry->setUseVertexBufferObjects(true);
    return geometry;
}

osg::ref_ptr<osg::Geometry> makeSkinnedOutputGeometry(const osg::Geometry& bindPose)
{
    osg::ref_ptr<osg::Geometry> geometry = new osg::Geometry;
    geometry->setName(bindPose.getName());
    geometry->setUseDisplayList(false);
    geometry->setCullingActive(false);
    // Rewritten each frame it is drawn, by the CPU: a buffer object of their own, so that the static arrays are not
    // uploaded again with them.
    osg::ref_ptr<osg::VertexBufferObject> buffer = new osg::VertexBufferObject;
    buffer->setUsage(GL_DYNAMIC_DRAW_ARB);
    const unsigned numVertices = bindPose.getVertexArray()->getNumElements();
    osg::ref_ptr<osg::Vec3Array> positions = new osg::Vec3Array(numVertices);
    positions->setBufferObject(buffer.get());
    geometry->setVertexArray(positions.get());
    if (bindPose.getNormalArray())
    {
        osg::ref_ptr<osg::Vec3Array> normals = new osg::Vec3Array(numVertices);
        normals->setBufferObject(buffer.get());
        geometry->setNormalArray(normals.get(), osg::Array::BIND_PER_VERTEX);
    }
    if (bindPose.getColorArray()) geometry->setColorArray(const_cast<osg::Array*>(bindPose.getColorArray()));
    geometry->setTexCoordArrayList(bindPose.getTexCoordArrayList());
    geometry->setPrimitiveSetList(bindPose.getPrimitiveSetList());
    geometry->setUseVertexBufferObjects(true);
    return geometry;
}

} // namespace osgActor
