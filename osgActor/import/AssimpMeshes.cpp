// The Assimp reader's meshes and skins (AssimpScene): one primitive per aiMesh, one skin per aiMesh with bones.
#include "AssimpScene"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace osgActor {
namespace assimp {

namespace {

bool finite(const aiVector3D& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

class MeshReader
{
public:
    MeshReader(SceneReading& reading, unsigned index)
        : _reading(reading), _source(*reading.scene.mMeshes[index]),
          _place(place("meshes", index, reading.scene.mMeshes[index]->mName))
    {
    }

    /** The mesh, and its skin's index in the model (or -1). */
    int read(RiggedMesh& mesh)
    {
        mesh.name = _source.mName.C_Str();
        if (!(_source.mPrimitiveTypes & aiPrimitiveType_TRIANGLE))
        {
            _reading.warn(_place + ": holds only points or lines, which are left out");
            return -1;
        }
        if (_source.mNumAnimMeshes > 0)
            _reading.warn(_place + ": " + std::to_string(_source.mNumAnimMeshes) + " morph targets are left out");
        RiggedPrimitive primitive;
        primitive.place = _place;
        readVertices(primitive);
        readTriangles(primitive);
        if (_source.mMaterialIndex >= _reading.scene.mNumMaterials)
            throw Refusal(_place, "material " + std::to_string(_source.mMaterialIndex) + " does not exist");
        primitive.material = int(_source.mMaterialIndex);
        const int skin = _source.mNumBones > 0 ? readSkin(primitive) : -1;
        mesh.primitives.push_back(std::move(primitive));
        return skin;
    }

private:
    void readVertices(RiggedPrimitive& primitive)
    {
        const unsigned count = _source.mNumVertices;
        if (count == 0 || !_source.mVertices) throw Refusal(_place, "has no vertices");
        primitive.positions.resize(count);
        for (unsigned v = 0; v < count; ++v)
        {
            const aiVector3D& p = _source.mVertices[v];
            if (!finite(p)) throw Refusal(_place, "vertex " + std::to_string(v) + "'s position is not finite");
            primitive.positions[v] = glm::vec3(p.x, p.y, p.z);
        }
        if (_source.mNormals)
        {
            const bool usable = std::all_of(_source.mNormals, _source.mNormals + count, finite);
            if (usable)
                for (unsigned v = 0; v < count; ++v)
                    primitive.normals.emplace_back(_source.mNormals[v].x, _source.mNormals[v].y, _source.mNormals[v].z);
            else _reading.warn(_place + ": a normal is not finite; the normals are left out");
        }
        if (!primitive.normals.empty() && _source.mTangents && _source.mBitangents &&
            std::all_of(_source.mTangents, _source.mTangents + count, finite) &&
            std::all_of(_source.mBitangents, _source.mBitangents + count, finite))
            for (unsigned v = 0; v < count; ++v)
            {
                const glm::vec3 t(_source.mTangents[v].x, _source.mTangents[v].y, _source.mTangents[v].z);
                const glm::vec3 b(_source.mBitangents[v].x, _source.mBitangents[v].y, _source.mBitangents[v].z);
                // glTF's convention: the bitangent is cross(normal, tangent) * w.
                const float w = glm::dot(glm::cross(primitive.normals[v], t), b) < 0.0f ? -1.0f : 1.0f;
                primitive.tangents.emplace_back(t, w);
            }
        readTexCoords(0, primitive.texCoords0);
        readTexCoords(1, primitive.texCoords1);
    }

    void readTexCoords(unsigned set, std::vector<glm::vec2>& out)
    {
        const aiVector3D* coords = _source.mTextureCoords[set];
        if (!coords) return;
        if (!std::all_of(coords, coords + _source.mNumVertices, finite))
        {
            _reading.warn(_place + ": texture coordinate set " + std::to_string(set) +
                          " holds a number that is not finite and is left out");
            return;
        }
        for (unsigned v = 0; v < _source.mNumVertices; ++v) out.emplace_back(coords[v].x, coords[v].y);
    }

    void readTriangles(RiggedPrimitive& primitive)
    {
        if (_source.mNumFaces > 0 && !_source.mFaces) throw Refusal(_place, "has no list of its faces");
        std::size_t left = 0;
        for (unsigned f = 0; f < _source.mNumFaces; ++f)
        {
            const aiFace& face = _source.mFaces[f];
            if (face.mNumIndices != 3)
            {
                ++left; // a point or line Assimp left in a triangle mesh
                continue;
            }
            for (unsigned i = 0; i < 3; ++i)
            {
                if (face.mIndices[i] >= _source.mNumVertices)
                    throw Refusal(_place, "face " + std::to_string(f) + " names vertex " +
                                              std::to_string(face.mIndices[i]) + " of " +
                                              std::to_string(_source.mNumVertices));
                primitive.indices.push_back(face.mIndices[i]);
            }
        }
        if (left > 0) _reading.warn(_place + ": " + std::to_string(left) + " faces that are not triangles are left out");
    }

    /** The skin (bones by node name, offset matrices as inverse bind matrices) and the vertices' influences: the
      * largest eight per vertex (renormalised later, by the skin). */
    int readSkin(RiggedPrimitive& primitive)
    {
        if (!_source.mBones) throw Refusal(_place, "has no list of its bones");
        if (_source.mNumBones > std::numeric_limits<std::uint16_t>::max())
            throw Refusal(_place, "has more bones than a skin takes (65535)");
        RiggedSkin skin;
        skin.name = _source.mName.C_Str();
        std::vector<std::vector<JointWeight>> influences(_source.mNumVertices);
        for (unsigned b = 0; b < _source.mNumBones; ++b)
        {
            const aiBone* bone = _source.mBones[b];
            if (!bone) throw Refusal(_place, "bones[" + std::to_string(b) + "] is missing");
            const std::string where = _place + "." + place("bones", b, bone->mName);
            const int node = _reading.findNode(bone->mName);
            if (node < 0) throw Refusal(where, "names no node of the scene");
            const auto listed = std::find(skin.joints.begin(), skin.joints.end(), node);
            if (listed != skin.joints.end())
                throw Refusal(where, "names the node of bones[" + std::to_string(listed - skin.joints.begin()) + "] again");
            const glm::dmat4 offset = toGlm(bone->mOffsetMatrix);
            for (int i = 0; i < 16; ++i)
                if (!std::isfinite(offset[i / 4][i % 4])) throw Refusal(where, "its offset matrix is not finite");
            skin.joints.push_back(node);
            skin.inverseBindMatrices.push_back(offset);
            if (bone->mNumWeights > 0 && !bone->mWeights) throw Refusal(where, "has no list of its weights");
            for (unsigned w = 0; w < bone->mNumWeights; ++w)
            {
                const aiVertexWeight& weight = bone->mWeights[w];
                if (weight.mVertexId >= _source.mNumVertices)
                    throw Refusal(where, "weights vertex " + std::to_string(weight.mVertexId) + " of " +
                                             std::to_string(_source.mNumVertices));
                if (!(weight.mWeight >= 0.0f) || !std::isfinite(weight.mWeight))
                    throw Refusal(where, "its weight on vertex " + std::to_string(weight.mVertexId) +
                                             " is not a finite number >= 0");
                if (weight.mWeight > 0.0f)
                    influences[weight.mVertexId].push_back(JointWeight{std::uint16_t(b), weight.mWeight});
            }
        }
        writeInfluences(influences, primitive);
        _reading.model.skins.push_back(std::move(skin));
        return int(_reading.model.skins.size()) - 1;
    }

    void writeInfluences(std::vector<std::vector<JointWeight>>& influences, RiggedPrimitive& primitive)
    {
        for (std::size_t v = 0; v < influences.size(); ++v)
            if (influences[v].empty())
                throw Refusal(_place, "vertex " + std::to_string(v) + " is weighted by no bone (its weights sum to zero)");
        const std::size_t cut = setInfluences(primitive, influences);
        if (cut > 0)
            _reading.warn(_place + ": " + std::to_string(cut) + " vertices have more than eight bones; the eight " +
                          "largest weights are kept");
    }

    SceneReading& _reading;
    const aiMesh& _source;
    const std::string _place;
};

} // namespace

void readMeshes(SceneReading& reading)
{
    const aiScene& scene = reading.scene;
    if (scene.mNumMeshes > 0 && !scene.mMeshes) throw Refusal("scene", "has no list of its meshes");
    std::vector<int> skinOfMesh(scene.mNumMeshes, -1);
    for (unsigned m = 0; m < scene.mNumMeshes; ++m)
    {
        if (!scene.mMeshes[m]) throw Refusal("meshes[" + std::to_string(m) + "]", "is missing");
        RiggedMesh mesh;
        skinOfMesh[m] = MeshReader(reading, m).read(mesh);
        reading.model.meshes.push_back(std::move(mesh));
    }
    // Which node draws which mesh: the first of a node's meshes at the node, each further one at a child node of
    // its own (a node draws one mesh), added after the file's nodes so that those keep their depth-first indices.
    const std::size_t fileNodes = reading.model.nodes.size();
    for (std::size_t n = 0; n < fileNodes; ++n)
    {
        const aiNode& source = *reading.sourceNodes[n];
        if (source.mNumMeshes > 0 && !source.mMeshes)
            throw Refusal(place("nodes", n, source.mName), "has no list of its meshes");
        for (unsigned k = 0; k < source.mNumMeshes; ++k)
        {
            const unsigned m = source.mMeshes[k];
            if (m >= scene.mNumMeshes)
                throw Refusal(place("nodes", n, source.mName), "mesh " + std::to_string(m) + " does not exist");
            if (reading.model.meshes[m].primitives.empty()) continue;
            int drawer = int(n);
            if (reading.model.nodes[n].mesh >= 0)
            {
                RiggedNode extra;
                extra.name = reading.model.nodes[n].name + "/" +
                             (scene.mMeshes[m]->mName.length > 0 ? std::string(scene.mMeshes[m]->mName.C_Str())
                                                                 : "mesh" + std::to_string(m));
                extra.parent = int(n);
                drawer = int(reading.model.nodes.size());
                reading.model.nodes.push_back(extra);
            }
            reading.model.nodes[drawer].mesh = int(m);
            reading.model.nodes[drawer].skin = skinOfMesh[m];
        }
    }
}

} // namespace assimp
} // namespace osgActor
