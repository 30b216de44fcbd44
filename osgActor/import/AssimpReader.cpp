#include <osgActor/import/AssimpReader>

#include "AssimpScene"

#include <osgActor/mocap/MocapImport>

#include <assimp/Importer.hpp>
#include <assimp/config.h>
#include <assimp/postprocess.h>

#include <algorithm>
#include <set>

namespace osgActor {

namespace assimp {

int SceneReading::findNode(const aiString& name) const
{
    const auto found = nodeByName.find(name.C_Str());
    return found == nodeByName.end() ? -1 : found->second;
}

std::string place(const char* array, std::size_t index, const aiString& name)
{
    std::string text = std::string(array) + "[" + std::to_string(index) + "]";
    if (name.length > 0) text += " '" + std::string(name.C_Str()) + "'";
    return text;
}

glm::dmat4 toGlm(const aiMatrix4x4& m)
{
    glm::dmat4 out;
    for (unsigned row = 0; row < 4; ++row)
        for (unsigned column = 0; column < 4; ++column) out[column][row] = m[row][column];
    return out;
}

void readNodes(SceneReading& reading)
{
    const aiNode* root = reading.scene.mRootNode;
    if (!root) throw Refusal("scene", "has no root node");
    // Depth first, parents before children, siblings in the file's order: the order aiNode::FindNode searches in.
    std::vector<std::pair<const aiNode*, int>> pending{{root, -1}};
    std::set<const aiNode*> seen;
    while (!pending.empty())
    {
        const aiNode* source = pending.back().first;
        const int parent = pending.back().second;
        pending.pop_back();
        const int index = int(reading.model.nodes.size());
        const std::string where = place("nodes", std::size_t(index), source->mName);
        if (!seen.insert(source).second) throw Refusal(where, "appears twice in the node tree");
        RiggedNode node;
        node.name = source->mName.C_Str();
        node.parent = parent;
        bool shear = false;
        const std::string problem = decomposeNodeMatrix(toGlm(source->mTransformation), node, shear);
        if (!problem.empty()) throw Refusal(where, "its transformation " + problem);
        if (shear) reading.warn(where + ": its transformation has shear, which is left out");
        reading.nodeByName.emplace(node.name, index);
        reading.model.nodes.push_back(node);
        reading.sourceNodes.push_back(source);
        if (source->mNumChildren > 0 && !source->mChildren) throw Refusal(where, "has no list of its children");
        for (unsigned c = source->mNumChildren; c-- > 0;)
        {
            if (!source->mChildren[c]) throw Refusal(where, "child " + std::to_string(c) + " is missing");
            pending.emplace_back(source->mChildren[c], index);
        }
    }
    reading.model.sceneRoots.assign(1, 0);
}

RiggedModelRead readScene(const aiScene& scene, const std::string& name, const std::string& folder)
{
    RiggedModelRead result;
    try
    {
        auto model = std::make_shared<RiggedModel>();
        model->sourceFile = name;
        SceneReading reading{scene, *model, result.warnings, folder, {}, {}};
        readNodes(reading);
        readMeshes(reading);
        readMaterials(reading);
        readAnimations(reading);
        for (int n : makeNodeNamesUnique(*model))
            reading.warn("nodes[" + std::to_string(n) + "]: a second node of its name is called '" +
                         model->nodes[n].name + "'");
        makeAnimationNamesUnique(*model);
        if (scene.mNumCameras > 0) reading.warn(std::to_string(scene.mNumCameras) + " cameras are left out");
        if (scene.mNumLights > 0) reading.warn(std::to_string(scene.mNumLights) + " lights are left out");
        for (std::string& warning : result.warnings) warning = name + ": " + warning;
        result.model = model;
        return result;
    }
    catch (const Refusal& refusal)
    {
        result.error = name + ": " + refusal.what();
    }
    catch (const std::bad_alloc&)
    {
        result.error = name + ": not enough memory to read it";
    }
    result.warnings.clear();
    return result;
}

} // namespace assimp

namespace {

/** The extensions readAssimpFile() is used for: the formats Assimp reads with skeletons. */
const char* const kExtensions[] = {".dae", ".zae", ".fbx", ".x", ".b3d", ".md5mesh", ".smd", ".ms3d", ".ogex", ".iqm"};

/** Assimp's post-processing, chosen so that the scene stays the file's: nothing that bakes transforms into vertices
  * (PreTransformVertices), merges or removes nodes (OptimizeGraph, OptimizeMeshes, Debone), or changes handedness.
  * Triangulate: polygons become triangles. JoinIdenticalVertices: indexed meshes (Collada, X and FBX give one
  * vertex per face corner). LimitBoneWeights (with AI_CONFIG_PP_LBW_MAX_WEIGHTS 8): at most eight bones per vertex,
  * the largest, renormalised. SortByPType: points and lines in meshes of their own, left out with a warning.
  * ValidateDataStructure: Assimp checks its own output's indices (faces, bones' vertices, materials) before we do.
  * FlipUVs: texture coordinate v = 0 at the image's first row, as RiggedModel has it (Assimp's is the last). */
constexpr unsigned kPostProcessing = aiProcess_Triangulate | aiProcess_JoinIdenticalVertices |
                                     aiProcess_LimitBoneWeights | aiProcess_SortByPType |
                                     aiProcess_ValidateDataStructure | aiProcess_FlipUVs;

void configure(Assimp::Importer& importer)
{
    importer.SetPropertyInteger(AI_CONFIG_PP_LBW_MAX_WEIGHTS, 8);
    // FBX pivots and offsets folded into each node's transformation (and its animation keys) instead of chains of
    // "<name>_$AssimpFbx$_<part>" helper nodes; a helper that still comes is an ordinary node.
    importer.SetPropertyBool(AI_CONFIG_IMPORT_FBX_PRESERVE_PIVOTS, false);
}

RiggedModelRead convert(const Assimp::Importer& importer, const aiScene* scene, const std::string& name,
                        const std::string& folder)
{
    if (scene) return assimp::readScene(*scene, name, folder);
    RiggedModelRead failed;
    std::string error = importer.GetErrorString();
    std::replace(error.begin(), error.end(), '\n', ';');
    failed.error = name + ": Assimp cannot read it: " + (error.empty() ? std::string("no reason given") : error);
    return failed;
}

/** The folder of a path with its separator ("models/hero.fbx" gives "models/"), empty for a bare file name. */
std::string folderOf(const std::string& path)
{
    const std::size_t slash = path.find_last_of("/\\");
    return slash == std::string::npos ? std::string("./") : path.substr(0, slash + 1);
}

} // namespace

bool isAssimpModelFile(const std::string& path)
{
    const std::string extension = lowerExtensionOf(path);
    return std::find(std::begin(kExtensions), std::end(kExtensions), extension) != std::end(kExtensions);
}

RiggedModelRead readAssimpFile(const std::string& path)
{
    Assimp::Importer importer;
    configure(importer);
    const aiScene* scene = importer.ReadFile(path, kPostProcessing);
    return convert(importer, scene, path, folderOf(path));
}

RiggedModelRead readAssimpMemory(const void* bytes, std::size_t size, const std::string& formatHint,
                                 const std::string& name)
{
    Assimp::Importer importer;
    configure(importer);
    const aiScene* scene = importer.ReadFileFromMemory(bytes, size, kPostProcessing, formatHint.c_str());
    return convert(importer, scene, name, std::string());
}

} // namespace osgActor
