#include <osgActor/import/GltfReader>

#include "GltfAccessors"
#include "ImageDecoding"

#include <glm/ext/quaternion_geometric.hpp>
#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <iterator>
#include <limits>
#include <map>
#include <set>
#include <string>
#include <vector>

namespace osgActor {

namespace {

using gltf::AccessorData;
using gltf::AccessorRule;
using gltf::Refusal;
using gltf::readAccessor;

constexpr int kFloat = TINYGLTF_COMPONENT_TYPE_FLOAT;
constexpr int kUByte = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
constexpr int kUShort = TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
constexpr int kUInt = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
constexpr int kByte = TINYGLTF_COMPONENT_TYPE_BYTE;
constexpr int kShort = TINYGLTF_COMPONENT_TYPE_SHORT;

std::string indexed(const char* array, std::size_t index) { return std::string(array) + "[" + std::to_string(index) + "]"; }

/** tinygltf's image callback: keeps the encoded bytes of an image given by a URI, to decode once the whole file is
  * checked, and reads nothing of an image in a buffer view (tinygltf hands those over before any range is checked;
  * they are read from the checked view later). */
bool keepEncodedImage(tinygltf::Image* image, const int, std::string*, std::string*, int, int,
                      const unsigned char* bytes, int size, void*)
{
    if (image->bufferView < 0 && bytes && size > 0) image->image.assign(bytes, bytes + size);
    return true;
}

/** tinygltf's messages, one line each, without the trailing newline. */
std::string oneLine(std::string text)
{
    while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) text.pop_back();
    std::replace(text.begin(), text.end(), '\n', ';');
    return text;
}

/** Converts tinygltf's parsed model into a RiggedModel, checking everything it reads; throws Refusal. */
class Converter
{
public:
    Converter(const tinygltf::Model& gltf, RiggedModel& model, std::vector<std::string>& warnings)
        : _gltf(gltf), _model(model), _warnings(warnings)
    {
    }

    void convert()
    {
        warnAboutUnsupportedParts();
        readNodes();
        readSceneRoots();
        readSkins();
        readImages();
        readMaterials();
        readMeshes();
        checkSkinnedMeshes();
        readAnimations();
    }

private:
    void warn(const std::string& text) { _warnings.push_back(text); }

    void warnAboutUnsupportedParts()
    {
        for (const std::string& name : _gltf.extensionsUsed)
        {
            const bool required = std::find(_gltf.extensionsRequired.begin(), _gltf.extensionsRequired.end(), name) !=
                                  _gltf.extensionsRequired.end();
            warn("extension " + name + (required ? " (required by the file)" : "") +
                 " is not supported; what it adds is left out");
        }
        if (!_gltf.cameras.empty()) warn(std::to_string(_gltf.cameras.size()) + " cameras are left out");
    }

    // --- nodes ---

    void readNodes()
    {
        const std::size_t count = _gltf.nodes.size();
        _model.nodes.resize(count);
        for (std::size_t n = 0; n < count; ++n)
        {
            const tinygltf::Node& source = _gltf.nodes[n];
            RiggedNode& node = _model.nodes[n];
            const std::string place = indexed("nodes", n);
            readTransform(source, node, place);
            node.name = source.name; // "node<i>" when empty (makeNodeNamesUnique)
            if (source.mesh >= 0 && std::size_t(source.mesh) >= _gltf.meshes.size())
                throw Refusal(place, "mesh " + std::to_string(source.mesh) + " does not exist");
            if (source.skin >= 0 && std::size_t(source.skin) >= _gltf.skins.size())
                throw Refusal(place, "skin " + std::to_string(source.skin) + " does not exist");
            node.mesh = source.mesh;
            node.skin = source.mesh >= 0 ? source.skin : -1;
            if (!source.weights.empty()) warn(place + ": morph target weights are left out");
        }
        for (int n : makeNodeNamesUnique(_model))
        {
            const std::string& renamed = _model.nodes[n].name;
            const std::string original = renamed.substr(0, renamed.rfind('#'));
            warn(indexed("nodes", n) + ": a second node named '" + original + "' is called '" + renamed + "'");
        }
        // Parents from the children lists: each node has at most one parent and is not its own ancestor.
        for (std::size_t n = 0; n < count; ++n)
            for (int child : _gltf.nodes[n].children)
            {
                const std::string place = indexed("nodes", n);
                if (child < 0 || std::size_t(child) >= count)
                    throw Refusal(place, "child " + std::to_string(child) + " is not a node");
                int& parent = _model.nodes[child].parent;
                if (parent >= 0)
                    throw Refusal(indexed("nodes", child), "is a child of both nodes[" + std::to_string(parent) +
                                                               "] and nodes[" + std::to_string(n) + "]");
                parent = int(n);
            }
        for (std::size_t n = 0; n < count; ++n)
        {
            std::size_t steps = 0;
            for (int a = _model.nodes[n].parent; a >= 0; a = _model.nodes[a].parent)
                if (++steps > count || a == int(n))
                    throw Refusal(indexed("nodes", n), "is its own ancestor (the node hierarchy has a cycle)");
        }
    }

    static bool allFinite(const std::vector<double>& values)
    {
        return std::all_of(values.begin(), values.end(), [](double v) { return std::isfinite(v); });
    }

    void readTransform(const tinygltf::Node& source, RiggedNode& node, const std::string& place)
    {
        auto checkSize = [&](const std::vector<double>& values, std::size_t size, const char* what) {
            if (!values.empty() && values.size() != size)
                throw Refusal(place, std::string(what) + " has " + std::to_string(values.size()) + " numbers, not " +
                                         std::to_string(size));
            if (!allFinite(values)) throw Refusal(place, std::string(what) + " holds a number that is not finite");
        };
        checkSize(source.translation, 3, "translation");
        checkSize(source.rotation, 4, "rotation");
        checkSize(source.scale, 3, "scale");
        checkSize(source.matrix, 16, "matrix");
        if (!source.matrix.empty())
        {
            decomposeMatrix(source.matrix, node, place);
            return;
        }
        if (!source.translation.empty())
            node.translation = glm::dvec3(source.translation[0], source.translation[1], source.translation[2]);
        if (!source.rotation.empty())
            node.rotation = unitQuaternion(source.rotation[3], source.rotation[0], source.rotation[1],
                                           source.rotation[2], place + ": rotation");
        if (!source.scale.empty()) node.scale = glm::dvec3(source.scale[0], source.scale[1], source.scale[2]);
    }

    /** A node matrix (column-major) as T * R * S; the shear such a matrix may hold is dropped with a warning. */
    void decomposeMatrix(const std::vector<double>& m, RiggedNode& node, const std::string& place)
    {
        glm::dmat4 matrix;
        for (int i = 0; i < 16; ++i) matrix[i / 4][i % 4] = m[i];
        bool shear = false;
        const std::string problem = decomposeNodeMatrix(matrix, node, shear);
        if (!problem.empty()) throw Refusal(place, "matrix " + problem);
        if (shear) warn(place + ": matrix has shear, which is left out");
    }

    static glm::dquat unitQuaternion(double w, double x, double y, double z, const std::string& place)
    {
        const glm::dquat q(w, x, y, z);
        const double length = glm::length(q);
        if (!(length > 1e-6)) throw Refusal(place, "is a zero quaternion, not a rotation");
        return q / length;
    }

    void readSceneRoots()
    {
        if (_gltf.scenes.empty())
        {
            for (std::size_t n = 0; n < _model.nodes.size(); ++n)
                if (_model.nodes[n].parent < 0) _model.sceneRoots.push_back(int(n));
            return;
        }
        int scene = _gltf.defaultScene;
        if (scene < 0) scene = 0;
        if (std::size_t(scene) >= _gltf.scenes.size())
            throw Refusal("scene", "scene " + std::to_string(scene) + " does not exist");
        if (_gltf.scenes.size() > 1)
            warn(std::to_string(_gltf.scenes.size()) + " scenes: only scenes[" + std::to_string(scene) + "] is read");
        for (int root : _gltf.scenes[scene].nodes)
        {
            if (root < 0 || std::size_t(root) >= _model.nodes.size())
                throw Refusal(indexed("scenes", scene), "node " + std::to_string(root) + " does not exist");
            if (_model.nodes[root].parent >= 0)
                throw Refusal(indexed("scenes", scene), "nodes[" + std::to_string(root) + "] is not a root node");
            _model.sceneRoots.push_back(root);
        }
    }

    // --- skins ---

    void readSkins()
    {
        static const AccessorRule kInverseBind{"inverseBindMatrices", {TINYGLTF_TYPE_MAT4}, {kFloat}};
        for (std::size_t s = 0; s < _gltf.skins.size(); ++s)
        {
            const tinygltf::Skin& source = _gltf.skins[s];
            const std::string place = indexed("skins", s);
            RiggedSkin skin;
            skin.name = source.name;
            std::set<int> seen;
            for (std::size_t j = 0; j < source.joints.size(); ++j)
            {
                const int joint = source.joints[j];
                if (joint < 0 || std::size_t(joint) >= _model.nodes.size())
                    throw Refusal(place, "joints[" + std::to_string(j) + "] = " + std::to_string(joint) +
                                             " is not a node");
                if (!seen.insert(joint).second)
                    throw Refusal(place, "joints[" + std::to_string(j) + "]: nodes[" + std::to_string(joint) +
                                             "] is listed twice");
                skin.joints.push_back(joint);
            }
            if (skin.joints.empty()) throw Refusal(place, "has no joints");
            skin.inverseBindMatrices.assign(skin.joints.size(), glm::dmat4(1.0));
            if (source.inverseBindMatrices >= 0)
            {
                const AccessorData data = readAccessor(_gltf, source.inverseBindMatrices, kInverseBind, place);
                if (data.count < skin.joints.size())
                    throw Refusal(gltf::accessorPlace(source.inverseBindMatrices, kInverseBind, place),
                                  "has " + std::to_string(data.count) + " matrices for " +
                                      std::to_string(skin.joints.size()) + " joints");
                for (std::size_t j = 0; j < skin.joints.size(); ++j)
                    for (int i = 0; i < 16; ++i) skin.inverseBindMatrices[j][i / 4][i % 4] = data.at(j, i);
            }
            _model.skins.push_back(std::move(skin));
        }
    }

    // --- images, textures, materials ---

    void readImages()
    {
        _model.images.resize(_gltf.images.size());
        for (std::size_t i = 0; i < _gltf.images.size(); ++i)
        {
            const tinygltf::Image& source = _gltf.images[i];
            RiggedImage& image = _model.images[i];
            image.name = source.name;
            image.uri = source.uri.compare(0, 5, "data:") == 0 ? std::string() : source.uri;
            image.mimeType = source.mimeType;
            const std::string place = indexed("images", i);
            std::vector<unsigned char> encoded;
            if (source.bufferView >= 0)
            {
                if (std::size_t(source.bufferView) >= _gltf.bufferViews.size())
                    throw Refusal(place, "bufferView " + std::to_string(source.bufferView) + " does not exist");
                const tinygltf::BufferView& view = _gltf.bufferViews[source.bufferView];
                if (view.buffer < 0 || std::size_t(view.buffer) >= _gltf.buffers.size() ||
                    view.byteOffset > _gltf.buffers[view.buffer].data.size() ||
                    view.byteLength > _gltf.buffers[view.buffer].data.size() - view.byteOffset)
                    throw Refusal(indexed("bufferViews", source.bufferView), "reaches past its buffer");
                const unsigned char* begin = _gltf.buffers[view.buffer].data.data() + view.byteOffset;
                encoded.assign(begin, begin + view.byteLength);
            }
            else
                encoded = source.image;
            decodeImage(encoded, int(i), image, place);
        }
    }

    void decodeImage(const std::vector<unsigned char>& encoded, int index, RiggedImage& image, const std::string& place)
    {
        const std::string what = image.uri.empty() ? std::string("its embedded image") : "'" + image.uri + "'";
        if (encoded.empty())
        {
            warn(place + ": " + what + " cannot be read; materials using it are drawn untextured");
            return;
        }
        std::string error;
        if (!osgActor::decodeImage(encoded.data(), encoded.size(), index, image, error))
            warn(place + ": " + what + " cannot be decoded (" + error + "); materials using it are drawn untextured");
    }

    static TextureWrap wrapOf(int mode)
    {
        switch (mode)
        {
        case TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE: return TextureWrap::ClampToEdge;
        case TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT: return TextureWrap::MirroredRepeat;
        default: return TextureWrap::Repeat;
        }
    }

    static TextureFilter filterOf(int mode, TextureFilter otherwise)
    {
        switch (mode)
        {
        case TINYGLTF_TEXTURE_FILTER_NEAREST: return TextureFilter::Nearest;
        case TINYGLTF_TEXTURE_FILTER_LINEAR: return TextureFilter::Linear;
        case TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_NEAREST: return TextureFilter::NearestMipmapNearest;
        case TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_NEAREST: return TextureFilter::LinearMipmapNearest;
        case TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_LINEAR: return TextureFilter::NearestMipmapLinear;
        case TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_LINEAR: return TextureFilter::LinearMipmapLinear;
        default: return otherwise;
        }
    }

    void readMaterials()
    {
        for (std::size_t m = 0; m < _gltf.materials.size(); ++m)
        {
            const tinygltf::Material& source = _gltf.materials[m];
            const std::string place = indexed("materials", m);
            RiggedMaterial material;
            material.name = source.name;
            const std::vector<double>& factor = source.pbrMetallicRoughness.baseColorFactor;
            if (factor.size() != 4 || !allFinite(factor))
                throw Refusal(place, "baseColorFactor must be four finite numbers");
            material.baseColorFactor = glm::dvec4(factor[0], factor[1], factor[2], factor[3]);
            const tinygltf::TextureInfo& info = source.pbrMetallicRoughness.baseColorTexture;
            if (info.index >= 0)
            {
                if (std::size_t(info.index) >= _gltf.textures.size())
                    throw Refusal(place, "baseColorTexture " + std::to_string(info.index) + " is not a texture");
                const tinygltf::Texture& texture = _gltf.textures[info.index];
                const std::string texturePlace = indexed("textures", info.index);
                if (texture.source >= 0 && std::size_t(texture.source) >= _gltf.images.size())
                    throw Refusal(texturePlace, "source " + std::to_string(texture.source) + " is not an image");
                if (texture.sampler >= 0 && std::size_t(texture.sampler) >= _gltf.samplers.size())
                    throw Refusal(texturePlace, "sampler " + std::to_string(texture.sampler) + " is not a sampler");
                if (info.texCoord < 0 || info.texCoord > 1)
                    warn(place + ": baseColorTexture reads TEXCOORD_" + std::to_string(info.texCoord) +
                         ", which is not read; it is drawn untextured");
                else if (texture.source >= 0)
                {
                    material.baseColorTexture.image = texture.source;
                    material.baseColorTexture.texCoord = unsigned(info.texCoord);
                }
                if (texture.sampler >= 0)
                {
                    const tinygltf::Sampler& sampler = _gltf.samplers[texture.sampler];
                    material.baseColorTexture.wrapS = wrapOf(sampler.wrapS);
                    material.baseColorTexture.wrapT = wrapOf(sampler.wrapT);
                    material.baseColorTexture.minFilter = filterOf(sampler.minFilter, TextureFilter::LinearMipmapLinear);
                    material.baseColorTexture.magFilter = filterOf(sampler.magFilter, TextureFilter::Linear);
                }
            }
            if (source.alphaMode == "MASK") material.alphaMode = AlphaMode::Mask;
            else if (source.alphaMode == "BLEND") material.alphaMode = AlphaMode::Blend;
            if (!std::isfinite(source.alphaCutoff)) throw Refusal(place, "alphaCutoff is not finite");
            material.alphaCutoff = source.alphaCutoff;
            material.doubleSided = source.doubleSided;
            _model.materials.push_back(std::move(material));
        }
    }

    // --- meshes ---

    void readMeshes()
    {
        for (std::size_t m = 0; m < _gltf.meshes.size(); ++m)
        {
            RiggedMesh mesh;
            mesh.name = _gltf.meshes[m].name;
            if (_gltf.meshes[m].primitives.empty()) throw Refusal(indexed("meshes", m), "has no primitives");
            for (std::size_t p = 0; p < _gltf.meshes[m].primitives.size(); ++p)
                mesh.primitives.push_back(
                    readPrimitive(_gltf.meshes[m].primitives[p], indexed("meshes", m) + "." + indexed("primitives", p)));
            if (!_gltf.meshes[m].weights.empty())
                warn(indexed("meshes", m) + ": morph target weights are left out");
            _model.meshes.push_back(std::move(mesh));
        }
    }

    /** The accessor of an attribute, or -1. */
    static int attribute(const tinygltf::Primitive& primitive, const char* name)
    {
        const auto found = primitive.attributes.find(name);
        return found == primitive.attributes.end() ? -1 : found->second;
    }

    template <class Vec, unsigned N>
    std::vector<Vec> readVectors(const tinygltf::Primitive& source, const char* name, const AccessorRule& rule,
                                 std::size_t vertexCount, const std::string& place)
    {
        std::vector<Vec> out;
        const int index = attribute(source, name);
        if (index < 0) return out;
        const AccessorData data = readAccessor(_gltf, index, rule, place);
        if (data.count != vertexCount)
            throw Refusal(gltf::accessorPlace(index, rule, place),
                          "has " + std::to_string(data.count) + " elements for " + std::to_string(vertexCount) +
                              " vertices");
        out.resize(vertexCount);
        for (std::size_t v = 0; v < vertexCount; ++v)
            for (unsigned c = 0; c < N; ++c) out[v][c] = static_cast<float>(data.at(v, c));
        return out;
    }

    RiggedPrimitive readPrimitive(const tinygltf::Primitive& source, const std::string& place)
    {
        static const AccessorRule kPosition{"POSITION", {TINYGLTF_TYPE_VEC3}, {kFloat}};
        static const AccessorRule kNormal{"NORMAL", {TINYGLTF_TYPE_VEC3}, {kFloat}};
        static const AccessorRule kTangent{"TANGENT", {TINYGLTF_TYPE_VEC4}, {kFloat}};
        static const AccessorRule kTexCoord{"TEXCOORD", {TINYGLTF_TYPE_VEC2}, {kFloat, kUByte, kUShort}, true};
        static const AccessorRule kIndices{"indices", {TINYGLTF_TYPE_SCALAR}, {kUByte, kUShort, kUInt}};

        RiggedPrimitive primitive;
        primitive.place = place;
        if (source.material >= 0 && std::size_t(source.material) >= _gltf.materials.size())
            throw Refusal(place, "material " + std::to_string(source.material) + " does not exist");
        primitive.material = source.material;
        const int positions = attribute(source, "POSITION");
        if (positions < 0) throw Refusal(place, "has no POSITION attribute");
        const AccessorData positionData = readAccessor(_gltf, positions, kPosition, place);
        const std::size_t vertexCount = positionData.count;
        primitive.positions.resize(vertexCount);
        for (std::size_t v = 0; v < vertexCount; ++v)
            primitive.positions[v] = glm::vec3(positionData.at(v, 0), positionData.at(v, 1), positionData.at(v, 2));
        primitive.normals = readVectors<glm::vec3, 3>(source, "NORMAL", kNormal, vertexCount, place);
        primitive.tangents = readVectors<glm::vec4, 4>(source, "TANGENT", kTangent, vertexCount, place);
        primitive.texCoords0 = readVectors<glm::vec2, 2>(source, "TEXCOORD_0", kTexCoord, vertexCount, place);
        primitive.texCoords1 = readVectors<glm::vec2, 2>(source, "TEXCOORD_1", kTexCoord, vertexCount, place);
        readInfluences(source, primitive, vertexCount, place);
        if (!source.targets.empty())
            warn(place + ": " + std::to_string(source.targets.size()) + " morph targets are left out");

        std::vector<std::uint32_t> indices;
        if (source.indices >= 0)
        {
            const AccessorData data = readAccessor(_gltf, source.indices, kIndices, place);
            indices.resize(data.count);
            for (std::size_t i = 0; i < data.count; ++i)
            {
                if (data.values[i] >= double(vertexCount))
                    throw Refusal(place, "index " + std::to_string(std::uint64_t(data.values[i])) + " at position " +
                                             std::to_string(i) + " is out of range (" + std::to_string(vertexCount) +
                                             " vertices)");
                indices[i] = static_cast<std::uint32_t>(data.values[i]);
            }
        }
        else
        {
            if (vertexCount > std::numeric_limits<std::uint32_t>::max())
                throw Refusal(place, "has too many vertices");
            indices.resize(vertexCount);
            for (std::size_t i = 0; i < vertexCount; ++i) indices[i] = static_cast<std::uint32_t>(i);
        }
        primitive.indices = triangleList(indices, source.mode, place);
        return primitive;
    }

    /** Triangles from a primitive's indices in its mode; other modes (points, lines) give none, with a warning. */
    std::vector<std::uint32_t> triangleList(const std::vector<std::uint32_t>& indices, int mode, const std::string& place)
    {
        std::vector<std::uint32_t> triangles;
        switch (mode)
        {
        case TINYGLTF_MODE_TRIANGLES:
        case -1: // absent: triangles
            if (indices.size() % 3 != 0)
                throw Refusal(place, std::to_string(indices.size()) + " indices are not a whole number of triangles");
            return indices;
        case TINYGLTF_MODE_TRIANGLE_STRIP:
            for (std::size_t i = 2; i < indices.size(); ++i)
            {
                const bool even = i % 2 == 0; // keep every triangle's winding counter-clockwise
                triangles.insert(triangles.end(), {indices[i - 2], indices[even ? i - 1 : i], indices[even ? i : i - 1]});
            }
            return triangles;
        case TINYGLTF_MODE_TRIANGLE_FAN:
            for (std::size_t i = 2; i < indices.size(); ++i)
                triangles.insert(triangles.end(), {indices[0], indices[i - 1], indices[i]});
            return triangles;
        default:
            warn(place + ": points and lines (mode " + std::to_string(mode) + ") are left out");
            return triangles;
        }
    }

    void readInfluences(const tinygltf::Primitive& source, RiggedPrimitive& primitive, std::size_t vertexCount,
                        const std::string& place)
    {
        static const AccessorRule kJoints{"JOINTS", {TINYGLTF_TYPE_VEC4}, {kUByte, kUShort}};
        static const AccessorRule kWeights{"WEIGHTS", {TINYGLTF_TYPE_VEC4}, {kFloat, kUByte, kUShort}, true};
        const char* jointNames[2] = {"JOINTS_0", "JOINTS_1"};
        const char* weightNames[2] = {"WEIGHTS_0", "WEIGHTS_1"};
        unsigned sets = 0;
        for (unsigned set = 0; set < 2; ++set)
        {
            const bool hasJoints = attribute(source, jointNames[set]) >= 0;
            const bool hasWeights = attribute(source, weightNames[set]) >= 0;
            if (hasJoints != hasWeights)
                throw Refusal(place, std::string(hasJoints ? jointNames[set] : weightNames[set]) + " comes without " +
                                         (hasJoints ? weightNames[set] : jointNames[set]));
            if (!hasJoints) break;
            ++sets;
        }
        if (sets == 0) return;
        primitive.influencesPerVertex = 4 * sets;
        primitive.joints.resize(vertexCount * primitive.influencesPerVertex);
        primitive.weights.resize(vertexCount * primitive.influencesPerVertex);
        for (unsigned set = 0; set < sets; ++set)
        {
            const AccessorData joints = readAccessor(_gltf, attribute(source, jointNames[set]), kJoints, place);
            const AccessorData weights = readAccessor(_gltf, attribute(source, weightNames[set]), kWeights, place);
            if (joints.count != vertexCount || weights.count != vertexCount)
                throw Refusal(place, std::string(jointNames[set]) + " and " + weightNames[set] +
                                         " must have one element per vertex (" + std::to_string(vertexCount) + ")");
            for (std::size_t v = 0; v < vertexCount; ++v)
                for (unsigned c = 0; c < 4; ++c)
                {
                    const std::size_t slot = v * primitive.influencesPerVertex + set * 4 + c;
                    primitive.joints[slot] = static_cast<std::uint16_t>(joints.at(v, c));
                    primitive.weights[slot] = static_cast<float>(weights.at(v, c));
                    if (!(weights.at(v, c) >= 0.0))
                        throw Refusal(place, "vertex " + std::to_string(v) + " has a negative weight");
                }
        }
        for (std::size_t v = 0; v < vertexCount; ++v)
        {
            double sum = 0.0;
            for (unsigned i = 0; i < primitive.influencesPerVertex; ++i)
                sum += primitive.weights[v * primitive.influencesPerVertex + i];
            if (!(sum > 0.0)) throw Refusal(place, "vertex " + std::to_string(v) + "'s weights sum to zero");
        }
    }

    /** Every node that draws a skinned mesh names joints its skin has; a skin over a mesh without influences is
      * dropped (the mesh is drawn rigid) with a warning. */
    void checkSkinnedMeshes()
    {
        for (std::size_t n = 0; n < _model.nodes.size(); ++n)
        {
            RiggedNode& node = _model.nodes[n];
            if (node.skin < 0) continue;
            const std::size_t jointCount = _model.skins[node.skin].joints.size();
            for (const RiggedPrimitive& primitive : _model.meshes[node.mesh].primitives)
            {
                if (primitive.influencesPerVertex == 0)
                {
                    warn(indexed("nodes", n) + ": " + primitive.place +
                         " has no JOINTS_0/WEIGHTS_0; it is drawn rigid, not skinned");
                    continue;
                }
                for (std::size_t i = 0; i < primitive.joints.size(); ++i)
                    if (primitive.joints[i] >= jointCount && primitive.weights[i] > 0.0f)
                        throw Refusal(primitive.place, "vertex " + std::to_string(i / primitive.influencesPerVertex) +
                                                           " names joint " + std::to_string(primitive.joints[i]) +
                                                           " but skins[" + std::to_string(node.skin) + "] has " +
                                                           std::to_string(jointCount) + " joints");
            }
        }
    }

    // --- animations ---

    void readAnimations()
    {
        for (std::size_t a = 0; a < _gltf.animations.size(); ++a)
        {
            const tinygltf::Animation& source = _gltf.animations[a];
            const std::string place = indexed("animations", a);
            RiggedAnimation animation;
            animation.name = source.name; // "animation<i>" when empty (makeAnimationNamesUnique)
            bool morphWeights = false;
            for (std::size_t c = 0; c < source.channels.size(); ++c)
            {
                const tinygltf::AnimationChannel& channel = source.channels[c];
                const std::string channelPlace = place + "." + indexed("channels", c);
                if (channel.target_path == "weights")
                {
                    morphWeights = true;
                    continue;
                }
                if (channel.target_node < 0)
                {
                    warn(channelPlace + ": has no target node and is left out");
                    continue;
                }
                if (std::size_t(channel.target_node) >= _model.nodes.size())
                    throw Refusal(channelPlace, "target node " + std::to_string(channel.target_node) + " does not exist");
                if (channel.sampler < 0 || std::size_t(channel.sampler) >= source.samplers.size())
                    throw Refusal(channelPlace, "sampler " + std::to_string(channel.sampler) + " does not exist");
                AnimationChannel out;
                out.node = channel.target_node;
                if (channel.target_path == "translation") out.path = AnimationPath::Translation;
                else if (channel.target_path == "rotation") out.path = AnimationPath::Rotation;
                else if (channel.target_path == "scale") out.path = AnimationPath::Scale;
                else throw Refusal(channelPlace, "path '" + channel.target_path + "' is not a glTF target path");
                readSampler(source.samplers[channel.sampler], out,
                            place + "." + indexed("samplers", std::size_t(channel.sampler)));
                animation.channels.push_back(std::move(out));
            }
            if (morphWeights) warn(place + ": morph target weights are not animated (morph targets are left out)");
            _model.animations.push_back(std::move(animation));
        }
        makeAnimationNamesUnique(_model);
    }

    void readSampler(const tinygltf::AnimationSampler& sampler, AnimationChannel& channel, const std::string& place)
    {
        static const AccessorRule kInput{"input", {TINYGLTF_TYPE_SCALAR}, {kFloat}};
        static const AccessorRule kVectorOutput{"output", {TINYGLTF_TYPE_VEC3}, {kFloat}};
        static const AccessorRule kRotationOutput{"output", {TINYGLTF_TYPE_VEC4}, {kFloat, kByte, kUByte, kShort, kUShort}, true};
        if (sampler.interpolation == "STEP") channel.interpolation = KeyInterpolation::Step;
        else if (sampler.interpolation == "LINEAR" || sampler.interpolation.empty())
            channel.interpolation = KeyInterpolation::Linear;
        else if (sampler.interpolation == "CUBICSPLINE") channel.interpolation = KeyInterpolation::CubicSpline;
        else throw Refusal(place, "interpolation '" + sampler.interpolation + "' is not STEP, LINEAR or CUBICSPLINE");

        const AccessorData input = readAccessor(_gltf, sampler.input, kInput, place);
        if (input.count == 0) throw Refusal(place, "has no keys");
        channel.times = input.values;
        for (std::size_t k = 0; k < channel.times.size(); ++k)
        {
            if (channel.times[k] < 0.0)
                throw Refusal(gltf::accessorPlace(sampler.input, kInput, place),
                              "key " + std::to_string(k) + " has a negative time");
            if (k > 0 && !(channel.times[k] > channel.times[k - 1]))
                throw Refusal(gltf::accessorPlace(sampler.input, kInput, place),
                              "key times are not strictly increasing at key " + std::to_string(k));
        }
        const bool rotation = channel.path == AnimationPath::Rotation;
        const AccessorRule& outputRule = rotation ? kRotationOutput : kVectorOutput;
        const AccessorData output = readAccessor(_gltf, sampler.output, outputRule, place);
        const bool cubic = channel.interpolation == KeyInterpolation::CubicSpline;
        const std::size_t keys = input.count;
        if (output.count != keys * (cubic ? 3 : 1))
            throw Refusal(gltf::accessorPlace(sampler.output, outputRule, place),
                          "has " + std::to_string(output.count) + " elements for " + std::to_string(keys) + " keys" +
                              (cubic ? " (CUBICSPLINE needs three per key: in-tangent, value, out-tangent)" : ""));
        auto element = [&](std::size_t e) {
            glm::dvec4 v(0.0);
            for (unsigned c = 0; c < output.components; ++c) v[c] = output.at(e, c);
            return v;
        };
        for (std::size_t k = 0; k < keys; ++k)
        {
            glm::dvec4 value = element(cubic ? 3 * k + 1 : k);
            if (rotation && !cubic)
            {
                const glm::dquat q = unitQuaternion(value.w, value.x, value.y, value.z,
                                                    place + ": output key " + std::to_string(k));
                value = glm::dvec4(q.x, q.y, q.z, q.w);
            }
            channel.values.push_back(value);
            if (cubic)
            {
                channel.inTangents.push_back(element(3 * k));
                channel.outTangents.push_back(element(3 * k + 2));
            }
        }
    }

    const tinygltf::Model& _gltf;
    RiggedModel& _model;
    std::vector<std::string>& _warnings;
};

} // namespace

namespace {

/** File access for a model read from memory: none (the files it names are not read; they "exist", so that the
  * message is the reader's). */
bool anyFileExists(const std::string&, void*) { return true; }
std::string keepPath(const std::string& path, void*) { return path; }
bool readNoFile(std::vector<unsigned char>*, std::string* error, const std::string& path, void*)
{
    if (error) *error += "'" + path + "' is not read (the model was read from memory)";
    return false;
}
bool writeNoFile(std::string*, const std::string&, const std::vector<unsigned char>&, void*) { return false; }

/** Loads with tinygltf (load: the loader's call, file or memory) and converts: the reader's one path. */
template <class Load>
RiggedModelRead loadAndConvert(const std::string& name, tinygltf::TinyGLTF& loader, const Load& load)
{
    RiggedModelRead result;
    auto fail = [&](const std::string& message) {
        result.model.reset();
        result.warnings.clear();
        result.error = name + ": " + message;
        return result;
    };
    try
    {
        loader.SetImageLoader(&keepEncodedImage, nullptr);
        tinygltf::Model gltf;
        std::string error, warning;
        if (!load(gltf, error, warning)) return fail(oneLine(error.empty() ? "tinygltf cannot read it" : error));
        if (!warning.empty()) result.warnings.push_back(oneLine(warning));
        if (gltf.asset.version.compare(0, 2, "2.") != 0)
            return fail("asset.version '" + gltf.asset.version + "' is not glTF 2");

        auto model = std::make_shared<RiggedModel>();
        model->sourceFile = name;
        Converter(gltf, *model, result.warnings).convert();
        for (std::string& warningText : result.warnings) warningText = name + ": " + warningText;
        result.model = model;
        return result;
    }
    catch (const Refusal& refusal)
    {
        return fail(refusal.what());
    }
    catch (const std::bad_alloc&)
    {
        return fail("not enough memory to read it");
    }
    catch (const std::exception& exception)
    {
        return fail(std::string("tinygltf cannot read it (") + exception.what() + ")");
    }
}

bool isBinaryGltf(const char* magic, std::size_t size) { return size >= 4 && std::equal(magic, magic + 4, "glTF"); }

/** What is wrong with a binary glTF's framing (its header and chunks), or empty. Checked before tinygltf sees the
  * bytes: Debian's tinygltf 2.7 trusts a chunk's length and copies past the end of the input when a chunk claims
  * more bytes than the file holds. */
std::string glbFramingError(const unsigned char* bytes, std::size_t size)
{
    const auto word = [bytes](std::size_t at) {
        return std::uint32_t(bytes[at]) | std::uint32_t(bytes[at + 1]) << 8 | std::uint32_t(bytes[at + 2]) << 16 |
               std::uint32_t(bytes[at + 3]) << 24;
    };
    if (size < 12) return "a binary glTF (GLB) starts with a 12-byte header; the file has " + std::to_string(size);
    if (word(4) != 2) return "GLB version " + std::to_string(word(4)) + ", not 2";
    if (word(8) != size)
        return "the GLB header gives a length of " + std::to_string(word(8)) + " bytes; the file has " +
               std::to_string(size);
    std::size_t at = 12;
    unsigned chunk = 0;
    for (; at < size; ++chunk)
    {
        const std::string place = "GLB chunk " + std::to_string(chunk) + " at byte " + std::to_string(at);
        if (size - at < 8) return place + ": its 8-byte header runs past the end of the file";
        const std::uint32_t length = word(at);
        if (length > size - at - 8)
            return place + " claims " + std::to_string(length) + " bytes; " + std::to_string(size - at - 8) +
                   " remain in the file";
        if (chunk == 0 && word(at + 4) != 0x4E4F534Au) return place + " is not the JSON chunk a GLB starts with";
        at += 8 + std::size_t(length);
    }
    return chunk == 0 ? "the GLB holds no chunk" : "";
}

RiggedModelRead refused(const std::string& name, const std::string& error)
{
    RiggedModelRead failed;
    failed.error = name + ": " + error;
    return failed;
}

} // namespace

RiggedModelRead readGltfFile(const std::string& path)
{
    std::ifstream probe(path, std::ios::binary);
    if (!probe)
    {
        RiggedModelRead failed;
        failed.error = path + ": cannot open the file";
        return failed;
    }
    char magic[4] = {0, 0, 0, 0};
    probe.read(magic, 4);
    const bool binary = isBinaryGltf(magic, std::size_t(probe.gcount()));
    if (binary)
    {
        probe.seekg(0);
        const std::vector<unsigned char> whole((std::istreambuf_iterator<char>(probe)),
                                               std::istreambuf_iterator<char>());
        const std::string framing = glbFramingError(whole.data(), whole.size());
        if (!framing.empty()) return refused(path, framing);
    }
    probe.close();
    tinygltf::TinyGLTF loader;
    return loadAndConvert(path, loader, [&](tinygltf::Model& gltf, std::string& error, std::string& warning) {
        return binary ? loader.LoadBinaryFromFile(&gltf, &error, &warning, path)
                      : loader.LoadASCIIFromFile(&gltf, &error, &warning, path);
    });
}

RiggedModelRead readGltfMemory(const void* bytes, std::size_t size, const std::string& name)
{
    const char* text = static_cast<const char*>(bytes);
    if (size > std::numeric_limits<unsigned int>::max())
    {
        RiggedModelRead failed;
        failed.error = name + ": too large";
        return failed;
    }
    if (isBinaryGltf(text, size))
    {
        const std::string framing = glbFramingError(static_cast<const unsigned char*>(bytes), size);
        if (!framing.empty()) return refused(name, framing);
    }
    tinygltf::TinyGLTF loader;
    loader.SetFsCallbacks(tinygltf::FsCallbacks{&anyFileExists, &keepPath, &readNoFile, &writeNoFile, nullptr});
    return loadAndConvert(name, loader, [&](tinygltf::Model& gltf, std::string& error, std::string& warning) {
        return isBinaryGltf(text, size)
                   ? loader.LoadBinaryFromMemory(&gltf, &error, &warning,
                                                 reinterpret_cast<const unsigned char*>(text), unsigned(size))
                   : loader.LoadASCIIFromString(&gltf, &error, &warning, text, unsigned(size), "");
    });
}

} // namespace osgActor
