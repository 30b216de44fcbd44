/* osgActor::SkinnedMesh in OSG's serializer formats (.osgt, .osgb, .osgx), its skin inline:
 *
 *   Surface <osg::Geometry: texture coordinates and triangles>
 *   Skin {
 *     Name "<name>" Method LinearBlend|DualQuaternion NormalTransform LinearPart|InverseTranspose
 *     Joints <n> { "<joint name>" <inverse bind matrix: 16 numbers, column by column> ... }
 *     Vertices <n> Normals TRUE|FALSE Tangents TRUE|FALSE {
 *       <x y z> [<normal x y z>] [<tangent x y z w>] <k> <joint weight> x k ...     (bind space, the file's order)
 *     }
 *   }
 *   SkinningPath GPU_SKINNING|CPU_SKINNING
 *   PaletteStorage Automatic|UniformArray|TextureBuffer
 *
 * Numbers are written exactly (SerializedNumbers). Reading rebuilds the skin through SkinBuilder, which validates
 * everything: a broken skin fails the whole read with its message, and nothing is half-built. */
#include "SerializedLines"
#include "SerializedNumbers"

#include <osgActor/SkinnedMesh>
#include <osgActor/core/skin/SkinBuilder>

#include <osgDB/ObjectWrapper>

#include <array>

using namespace osgActorSerializers;

namespace {

const char* methodName(osgActor::SkinningMethod method)
{
    return method == osgActor::SkinningMethod::DualQuaternion ? "DualQuaternion" : "LinearBlend";
}

const char* normalTransformName(osgActor::NormalTransform transform)
{
    return transform == osgActor::NormalTransform::InverseTranspose ? "InverseTranspose" : "LinearPart";
}

template <class Vector>
void writeVector(osgDB::OutputStream& os, const Vector& v, int size)
{
    for (int i = 0; i < size; ++i) writeExact(os, v[i]);
}

template <class Vector>
Vector readVector(osgDB::InputStream& is, int size)
{
    Vector v(0.0f);
    for (int i = 0; i < size; ++i) v[i] = readExactNumber<float>(is, "skinned mesh: a vertex");
    return v;
}

} // namespace

static bool checkSkin(const osgActor::SkinnedMesh& mesh) { return mesh.getSkin() != nullptr; }

static bool writeSkin(osgDB::OutputStream& os, const osgActor::SkinnedMesh& mesh)
{
    const osgActor::Skin& skin = *mesh.getSkin();
    os << os.BEGIN_BRACKET << std::endl;
    os << os.PROPERTY("Name");
    os.writeWrappedString(skin.getName());
    os << os.PROPERTY("Method") << std::string(methodName(skin.getMethod()));
    os << os.PROPERTY("NormalTransform") << std::string(normalTransformName(skin.getNormalTransform())) << std::endl;

    os << os.PROPERTY("Joints");
    os.writeSize(skin.getNumJoints());
    os << os.BEGIN_BRACKET << std::endl;
    for (unsigned j = 0; j < skin.getNumJoints(); ++j)
    {
        os.writeWrappedString(skin.getJointName(j));
        const glm::dmat4& m = skin.getInverseBindMatrix(j);
        for (int c = 0; c < 4; ++c) writeVector(os, m[c], 4);
        os << std::endl;
    }
    os << os.END_BRACKET << std::endl;

    // Normals and tangents in the file's order: the skin keeps them grouped by influence count.
    const osgActor::SkinVertices grouped = skin.getVertices();
    std::vector<glm::vec3> normals(skin.hasNormals() ? skin.getNumVertices() : 0);
    std::vector<glm::vec4> tangents(skin.hasTangents() ? skin.getNumVertices() : 0);
    for (std::size_t i = 0; i < grouped.size(); ++i)
    {
        if (!normals.empty()) normals[grouped.outputIndices[i]] = grouped.normals[i];
        if (!tangents.empty()) tangents[grouped.outputIndices[i]] = grouped.tangents[i];
    }
    os << os.PROPERTY("Vertices");
    os.writeSize(skin.getNumVertices());
    os << os.PROPERTY("Normals") << skin.hasNormals() << os.PROPERTY("Tangents") << skin.hasTangents();
    os << os.BEGIN_BRACKET << std::endl;
    for (unsigned v = 0; v < skin.getNumVertices(); ++v)
    {
        writeVector(os, skin.getBindPosition(v), 3);
        if (!normals.empty()) writeVector(os, normals[v], 3);
        if (!tangents.empty()) writeVector(os, tangents[v], 4);
        const unsigned count = skin.getNumInfluences(v);
        os << count;
        for (unsigned k = 0; k < count; ++k)
        {
            os << static_cast<unsigned>(skin.getInfluenceJoints(v)[k]);
            writeExact(os, skin.getInfluenceWeights(v)[k]);
        }
        os << std::endl;
    }
    os << os.END_BRACKET << std::endl;
    os << os.END_BRACKET << std::endl;
    return true;
}

static bool readSkin(osgDB::InputStream& is, osgActor::SkinnedMesh& mesh)
{
    std::string name, method, normalTransform;
    is >> is.BEGIN_BRACKET >> is.PROPERTY("Name");
    is.readWrappedString(name);
    is >> is.PROPERTY("Method") >> method >> is.PROPERTY("NormalTransform") >> normalTransform;
    if (is.getException()) return false;
    osgActor::SkinBuilder builder(name);
    if (method == "DualQuaternion") builder.setMethod(osgActor::SkinningMethod::DualQuaternion);
    else if (method != "LinearBlend") return failRead(is, "skinned mesh: unknown skinning method '" + method + "'");
    if (normalTransform == "InverseTranspose") builder.setNormalTransform(osgActor::NormalTransform::InverseTranspose);
    else if (normalTransform == "LinearPart") builder.setNormalTransform(osgActor::NormalTransform::LinearPart);
    else return failRead(is, "skinned mesh: unknown normal transform '" + normalTransform + "'");

    is >> is.PROPERTY("Joints");
    const unsigned numJoints = is.readSize();
    is >> is.BEGIN_BRACKET;
    for (unsigned j = 0; j < numJoints && !is.getException(); ++j)
    {
        std::string joint;
        is.readWrappedString(joint);
        glm::dmat4 inverseBind(1.0);
        for (int c = 0; c < 4; ++c)
            for (int r = 0; r < 4; ++r) inverseBind[c][r] = readExact(is, "skinned mesh: an inverse bind matrix");
        builder.addJoint(joint, inverseBind);
    }
    is >> is.END_BRACKET;

    bool hasNormals = false, hasTangents = false;
    is >> is.PROPERTY("Vertices");
    const unsigned numVertices = is.readSize();
    is >> is.PROPERTY("Normals") >> hasNormals >> is.PROPERTY("Tangents") >> hasTangents >> is.BEGIN_BRACKET;
    std::vector<glm::vec3> positions, normals;
    std::vector<glm::vec4> tangents;
    std::vector<std::array<unsigned, osgActor::kMaxSkinInfluences>> joints;
    std::vector<std::array<float, osgActor::kMaxSkinInfluences>> weights;
    std::vector<unsigned> counts;
    for (unsigned v = 0; v < numVertices && !is.getException(); ++v)
    {
        positions.push_back(readVector<glm::vec3>(is, 3));
        if (hasNormals) normals.push_back(readVector<glm::vec3>(is, 3));
        if (hasTangents) tangents.push_back(readVector<glm::vec4>(is, 4));
        unsigned count = 0;
        is >> count;
        if (count > osgActor::kMaxSkinInfluences)
            return failRead(is, "skinned mesh: vertex " + std::to_string(v) + " has " + std::to_string(count) +
                                    " influences, more than " + std::to_string(osgActor::kMaxSkinInfluences));
        counts.push_back(count);
        joints.emplace_back();
        weights.emplace_back();
        for (unsigned k = 0; k < count; ++k)
        {
            is >> joints.back()[k];
            weights.back()[k] = readExactNumber<float>(is, "skinned mesh: an influence weight");
        }
    }
    is >> is.END_BRACKET >> is.END_BRACKET;
    if (is.getException()) return false;

    builder.setPositions(positions);
    builder.setNormals(normals);
    builder.setTangents(tangents);
    for (unsigned v = 0; v < numVertices; ++v) builder.addInfluences(v, joints[v].data(), weights[v].data(), counts[v]);
    const osgActor::SkinBuildResult built = builder.build();
    if (!built) return failRead(is, "skinned mesh: " + built.error);
    mesh.setSkin(built.skin);
    return true;
}

static bool checkPaletteStorage(const osgActor::SkinnedMesh&) { return true; }

static bool writePaletteStorage(osgDB::OutputStream& os, const osgActor::SkinnedMesh& mesh)
{
    const osgActor::SkinPaletteStorage storage = mesh.getPaletteStorage();
    os << std::string(storage == osgActor::SkinPaletteStorage::UniformArray
                          ? "UniformArray"
                          : (storage == osgActor::SkinPaletteStorage::TextureBuffer ? "TextureBuffer" : "Automatic"))
       << std::endl;
    return true;
}

static bool readPaletteStorage(osgDB::InputStream& is, osgActor::SkinnedMesh& mesh)
{
    std::string word;
    is >> word;
    if (word == "UniformArray") mesh.setPaletteStorage(osgActor::SkinPaletteStorage::UniformArray);
    else if (word == "TextureBuffer") mesh.setPaletteStorage(osgActor::SkinPaletteStorage::TextureBuffer);
    else if (word == "Automatic") mesh.setPaletteStorage(osgActor::SkinPaletteStorage::Automatic);
    else return failRead(is, "skinned mesh: unknown palette storage '" + word + "'");
    return true;
}

REGISTER_OBJECT_WRAPPER(osgActor_SkinnedMesh, new osgActor::SkinnedMesh, osgActor::SkinnedMesh,
                        "osg::Object osg::Node osg::Drawable osgActor::SkinnedMesh")
{
    ADD_OBJECT_SERIALIZER(Surface, osg::Geometry, NULL);
    ADD_USER_SERIALIZER(Skin);
    BEGIN_ENUM_SERIALIZER(SkinningPath, GPU_SKINNING);
        ADD_ENUM_VALUE(GPU_SKINNING);
        ADD_ENUM_VALUE(CPU_SKINNING);
    END_ENUM_SERIALIZER();
    ADD_USER_SERIALIZER(PaletteStorage);
}
