// libFuzzer target: the Assimp reader's own part, the conversion of an aiScene into a RiggedModel, and the mapping onto
// an actor, on scenes built from arbitrary bytes: node trees, meshes, bones, weights, animations and keys with any
// numbers (NaN, infinities), indices in and out of range, names that repeat or name nothing. Assimp's file parsers
// are not the subject: they are Assimp's to fuzz (its oss-fuzz target), and Debian's Assimp 5.2.5 aborts on some
// inputs (docs/import.md). The scenes hold what Assimp's post-processing guarantees: arrays as long as their
// counts, triangles only, at least one material. fuzz/RiggedContract says what the import must do.
#include "FuzzMain"
#include "RiggedContract"

#include <osgActor/import/AssimpScene>

#include <assimp/scene.h>
#include <fuzzer/FuzzedDataProvider.h>

#include <limits>
#include <vector>

namespace {

class SceneMaker
{
public:
    explicit SceneMaker(FuzzedDataProvider& in) : _in(in) {}

    aiScene* make()
    {
        aiScene* scene = new aiScene;
        scene->mNumMaterials = 1;
        scene->mMaterials = new aiMaterial*[1]{new aiMaterial};
        makeNodes(*scene);
        makeMeshes(*scene);
        makeAnimations(*scene);
        return scene;
    }

private:
    /** Mostly small numbers, sometimes the ones that break arithmetic. */
    float number()
    {
        switch (_in.ConsumeIntegralInRange(0, 15))
        {
        case 0: return std::numeric_limits<float>::quiet_NaN();
        case 1: return std::numeric_limits<float>::infinity();
        case 2: return _in.ConsumeFloatingPoint<float>();
        case 3: return 0.0f;
        default: return _in.ConsumeFloatingPointInRange(-4.0f, 4.0f);
        }
    }

    aiString name()
    {
        static const char* const kNames[] = {"root", "hip", "knee", "", "hip", "ghost"};
        return aiString(kNames[_in.ConsumeIntegralInRange(0, 5)]);
    }

    aiMatrix4x4 matrix()
    {
        aiMatrix4x4 m;
        if (_in.ConsumeBool()) m.a4 = number(), m.b4 = number(), m.c4 = number();
        else
            for (unsigned r = 0; r < 4; ++r)
                for (unsigned c = 0; c < 4; ++c) m[r][c] = number();
        return m;
    }

    void makeNodes(aiScene& scene)
    {
        const int count = _in.ConsumeIntegralInRange(1, 10);
        std::vector<aiNode*> nodes;
        std::vector<std::vector<aiNode*>> children(count);
        for (int n = 0; n < count; ++n)
        {
            nodes.push_back(new aiNode);
            nodes[n]->mName = name();
            nodes[n]->mTransformation = matrix();
            if (n > 0) children[_in.ConsumeIntegralInRange(0, n - 1)].push_back(nodes[n]);
        }
        for (int n = 0; n < count; ++n)
            if (!children[n].empty()) nodes[n]->addChildren(unsigned(children[n].size()), children[n].data());
        scene.mRootNode = nodes[0];
        _nodes = nodes;
    }

    void makeMeshes(aiScene& scene)
    {
        const unsigned count = _in.ConsumeIntegralInRange(0u, 3u);
        if (count == 0) return;
        scene.mNumMeshes = count;
        scene.mMeshes = new aiMesh*[count];
        for (unsigned m = 0; m < count; ++m) scene.mMeshes[m] = makeMesh();
        for (aiNode* node : _nodes)
        {
            if (!_in.ConsumeBool()) continue;
            node->mNumMeshes = _in.ConsumeIntegralInRange(1u, 2u);
            node->mMeshes = new unsigned[node->mNumMeshes];
            for (unsigned k = 0; k < node->mNumMeshes; ++k) node->mMeshes[k] = _in.ConsumeIntegralInRange(0u, count);
        }
    }

    aiMesh* makeMesh()
    {
        aiMesh* mesh = new aiMesh;
        mesh->mName = name();
        mesh->mPrimitiveTypes = aiPrimitiveType_TRIANGLE;
        mesh->mMaterialIndex = _in.ConsumeIntegralInRange(0u, 1u);
        const unsigned vertices = _in.ConsumeIntegralInRange(1u, 12u);
        mesh->mNumVertices = vertices;
        mesh->mVertices = new aiVector3D[vertices];
        for (unsigned v = 0; v < vertices; ++v) mesh->mVertices[v] = aiVector3D(number(), number(), number());
        if (_in.ConsumeBool())
        {
            mesh->mNormals = new aiVector3D[vertices];
            for (unsigned v = 0; v < vertices; ++v) mesh->mNormals[v] = aiVector3D(number(), number(), number());
        }
        mesh->mNumFaces = _in.ConsumeIntegralInRange(0u, 8u);
        mesh->mFaces = new aiFace[mesh->mNumFaces];
        for (unsigned f = 0; f < mesh->mNumFaces; ++f)
        {
            mesh->mFaces[f].mNumIndices = 3;
            mesh->mFaces[f].mIndices = new unsigned[3];
            for (unsigned i = 0; i < 3; ++i) mesh->mFaces[f].mIndices[i] = _in.ConsumeIntegralInRange(0u, vertices);
        }
        const unsigned bones = _in.ConsumeIntegralInRange(0u, 4u);
        if (bones == 0) return mesh;
        mesh->mNumBones = bones;
        mesh->mBones = new aiBone*[bones];
        for (unsigned b = 0; b < bones; ++b)
        {
            aiBone* bone = new aiBone;
            bone->mName = name();
            bone->mOffsetMatrix = matrix();
            bone->mNumWeights = _in.ConsumeIntegralInRange(0u, vertices + 1);
            bone->mWeights = new aiVertexWeight[bone->mNumWeights];
            for (unsigned w = 0; w < bone->mNumWeights; ++w)
                bone->mWeights[w] = aiVertexWeight(_in.ConsumeIntegralInRange(0u, vertices), number());
            mesh->mBones[b] = bone;
        }
        return mesh;
    }

    template <class Key, class Value>
    Key* keys(unsigned& count, Value (SceneMaker::*value)())
    {
        count = _in.ConsumeIntegralInRange(0u, 5u);
        Key* out = new Key[count];
        double time = 0.0;
        for (unsigned k = 0; k < count; ++k)
        {
            time += _in.ConsumeBool() ? double(number()) : 1.0;
            out[k].mTime = time;
            out[k].mValue = (this->*value)();
        }
        return out;
    }

    aiVector3D vector() { return aiVector3D(number(), number(), number()); }
    aiQuaternion quaternion() { return aiQuaternion(number(), number(), number(), number()); }

    void makeAnimations(aiScene& scene)
    {
        const unsigned count = _in.ConsumeIntegralInRange(0u, 2u);
        if (count == 0) return;
        scene.mNumAnimations = count;
        scene.mAnimations = new aiAnimation*[count];
        for (unsigned a = 0; a < count; ++a)
        {
            aiAnimation* animation = new aiAnimation;
            animation->mName = name();
            animation->mTicksPerSecond = _in.ConsumeBool() ? 0.0 : double(number());
            animation->mNumChannels = _in.ConsumeIntegralInRange(0u, 4u);
            // aiAnimation frees its channel list only when it has channels.
            if (animation->mNumChannels > 0) animation->mChannels = new aiNodeAnim*[animation->mNumChannels];
            for (unsigned c = 0; c < animation->mNumChannels; ++c)
            {
                aiNodeAnim* channel = new aiNodeAnim;
                channel->mNodeName = name();
                channel->mPositionKeys = keys<aiVectorKey>(channel->mNumPositionKeys, &SceneMaker::vector);
                channel->mRotationKeys = keys<aiQuatKey>(channel->mNumRotationKeys, &SceneMaker::quaternion);
                channel->mScalingKeys = keys<aiVectorKey>(channel->mNumScalingKeys, &SceneMaker::vector);
                animation->mChannels[c] = channel;
            }
            scene.mAnimations[a] = animation;
        }
    }

    FuzzedDataProvider& _in;
    std::vector<aiNode*> _nodes;
};

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    FuzzedDataProvider in(data, size);
    aiScene* scene = SceneMaker(in).make();
    const osgActor::RiggedModelRead read = osgActor::assimp::readScene(*scene, "input.assimp", std::string());
    delete scene;
    osgActor::fuzz::require(osgActor::contract::checkRiggedRead(read, "input.assimp"));
    return 0;
}
