// The Assimp reader (osgActor/import/AssimpReader): Collada, FBX and DirectX files into a RiggedModel. Bad files
// first (Debian's assimp-testmodels that are broken, and small DirectX files written here with one thing wrong
// each), then what real files map to.
#include "ImportTestUtil"

#include <osgActor/import/AssimpReader>
#include <osgActor/import/AssimpScene>
#include <osgActor/import/ChannelSampling>
#include <osgActor/import/RiggedActorBuilder>
#include <osgActor/import/RiggedModelFile>

#include <assimp/Exporter.hpp>
#include <assimp/Importer.hpp>
#include <assimp/scene.h>

#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <memory>

using namespace osgActor;
using namespace osgActor::test;

namespace {

/** tests/import/data/directx/chain.x: two bones, Upper 1 above the root and Lower 1 above it, skinning a quad from
  * 0.5 to 1.5 up; Lower turns a quarter about X (the key (w, x, y, z) = (0.7071, 0.7071, 0, 0)) from tick 0 to
  * tick 10, at 10 ticks per second. */
std::string chainFile() { return std::string(OSGACTOR_TEST_SOURCE_DIR) + "/import/data/directx/chain.x"; }

std::string chainText()
{
    std::ifstream in(chainFile(), std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

/** The chain with pieces of its text replaced (what, with), written into the build tree. */
std::string writeChain(const std::string& name, std::initializer_list<std::pair<const char*, const char*>> changes = {})
{
    std::string text = chainText();
    for (const auto& [what, with] : changes)
    {
        const std::size_t at = text.find(what);
        EXPECT_NE(at, std::string::npos) << what;
        if (at != std::string::npos) text.replace(at, std::string(what).size(), with);
    }
    const std::string path = written(name);
    std::ofstream(path, std::ios::binary) << text;
    return path;
}

/** The file refused with the message starting "path: place" and saying what, and nothing half-built. */
void expectRefused(const std::string& path, const std::string& place, const std::string& what)
{
    const RiggedModelRead read = readAssimpFile(path);
    EXPECT_FALSE(read.model);
    EXPECT_TRUE(read.warnings.empty());
    EXPECT_EQ(read.error.rfind(path + ": " + place, 0), 0u) << read.error;
    EXPECT_NE(read.error.find(what), std::string::npos) << read.error;
}

/** An aiScene read with Assimp and changed by the test, through Assimp's own binary format (assbin) in memory. */
RiggedModelRead readChanged(const std::string& path, void (*change)(aiScene&))
{
    Assimp::Importer importer;
    importer.ReadFile(path, 0);
    aiScene* scene = importer.GetOrphanedScene();
    if (!scene) return RiggedModelRead();
    change(*scene);
    Assimp::Exporter exporter;
    const aiExportDataBlob* blob = exporter.ExportToBlob(scene, "assbin");
    delete scene;
    EXPECT_TRUE(blob) << exporter.GetErrorString();
    if (!blob) return RiggedModelRead();
    return readAssimpMemory(blob->data, blob->size, "assbin", "changed.assbin");
}

} // namespace

// --- bad files first ---

TEST(AssimpReader, RefusesAFileItCannotOpen)
{
    expectRefused(written("missing.fbx"), "Assimp cannot read it", "Unable to open file");
}

TEST(AssimpReader, RefusesWhatAssimpCannotParseWithAssimpsOwnMessage)
{
    expectRefused(assimpModels("Collada/library_animation_clips.dae"), "Assimp cannot read it",
                  "Cannot parse string \"  0.0 0.0 0.0 1.0  \" as a real number");
    expectRefused(assimpModels("invalid/empty.x"), "Assimp cannot read it", "XFile is too small");
    expectRefused(assimpModels("FBX/transparentTest.fbx"), "Assimp cannot read it", "FBX-Tokenize");
    expectRefused(assimpModels("Collada/cube_UTF16LE.dae"), "Assimp cannot read it", "malformed XML");
    const std::string truncated = written("truncated.x");
    std::ofstream(truncated, std::ios::binary) << chainText().substr(0, chainText().find("    2;\n    3;0,1,2;"));
    expectRefused(truncated, "Assimp cannot read it", "Number expected");
}

TEST(AssimpReader, RefusesABoneThatNamesNoNode)
{
    // Debian's anim_test.x: its mesh names four bones, its hierarchy holds two (anim_test.txt says so).
    expectRefused(assimpModels("X/anim_test.x"), "meshes[0] 'pCylinder1'.bones[2] 'joint3'", "names no node of the scene");
    expectRefused(writeChain("ghost.x", {{"\"Lower\";", "\"Ghost\";"}}), "meshes[0] 'Root'.bones[1] 'Ghost'",
                  "names no node of the scene");
}

TEST(AssimpReader, RefusesAVertexNoBoneWeighs)
{
    expectRefused(writeChain("unweighted.x", {{"4;\n      0,1,2,3;\n      1.0,1.0,0.5,0.5;", "3;\n      0,1,2;\n      1.0,1.0,0.5;"},
                                              {"2;\n      2,3;\n      0.5,0.5;", "1;\n      2;\n      0.5;"}}),
                  "meshes[0] 'Root'", "vertex 3 is weighted by no bone");
}

TEST(AssimpReader, RefusesPositionsThatAreNotFinite)
{
    expectRefused(writeChain("nan.x", {{"0.0;0.5;0.0;,", "nan;0.5;0.0;,"}}), "meshes[0] 'Root'",
                  "vertex 0's position is not finite");
}

TEST(AssimpReader, RefusesKeysThatGoBack)
{
    expectRefused(writeChain("backwards.x", {{"10;4;0.70710678", "0;4;0.70710678"}}),
                  "animations[0] 'Bend'.channels[0] 'Lower'.rotationKeys", "key times are not strictly increasing at key 1");
}

TEST(AssimpReader, RefusesAZeroQuaternionKey)
{
    const RiggedModelRead read = readChanged(writeChain("chain_zero_quaternion.x"), [](aiScene& scene) {
        scene.mAnimations[0]->mChannels[0]->mRotationKeys[1].mValue = aiQuaternion(0.0f, 0.0f, 0.0f, 0.0f);
    });
    EXPECT_FALSE(read.model);
    EXPECT_EQ(read.error, "changed.assbin: animations[0] 'Bend'.channels[0] 'Lower'.rotationKeys: key 1 is a zero quaternion");
}

// --- what files map to ---

TEST(AssimpReader, ReadsTheChainsNodesSkinAndAnimation)
{
    const RiggedModelRead read = readAssimpFile(writeChain("chain_read.x"));
    ASSERT_TRUE(read) << read.error;
    const RiggedModel& model = *read.model;
    ASSERT_EQ(model.nodes.size(), 3u);
    EXPECT_EQ(model.nodes[0].name, "Root");
    EXPECT_EQ(model.nodes[1].name, "Upper");
    EXPECT_EQ(model.nodes[2].name, "Lower");
    EXPECT_EQ(model.nodes[2].parent, 1);
    EXPECT_DOUBLE_EQ(model.nodes[2].translation.y, 1.0);
    EXPECT_EQ(model.sceneRoots, std::vector<int>{0});
    // The mesh (drawn by the root, as the file puts it) and its skin: Upper and Lower with their offsets, 1 and 2 down.
    EXPECT_EQ(model.nodes[0].mesh, 0);
    EXPECT_EQ(model.nodes[0].skin, 0);
    ASSERT_EQ(model.skins.size(), 1u);
    EXPECT_EQ(model.skins[0].joints, (std::vector<int>{1, 2}));
    EXPECT_DOUBLE_EQ(model.skins[0].inverseBindMatrices[0][3].y, -1.0);
    EXPECT_DOUBLE_EQ(model.skins[0].inverseBindMatrices[1][3].y, -2.0);
    const RiggedPrimitive& quad = model.meshes.at(0).primitives.at(0);
    ASSERT_EQ(quad.getNumVertices(), 4u);
    EXPECT_EQ(quad.indices.size(), 6u);
    ASSERT_EQ(quad.influencesPerVertex, 4u);
    for (std::size_t v = 0; v < 4; ++v)
    {
        const bool top = quad.positions[v].y > 1.0f;
        EXPECT_EQ(quad.joints[v * 4], 0u) << v; // Upper: the largest (or first of two equal) weight
        EXPECT_FLOAT_EQ(quad.weights[v * 4], top ? 0.5f : 1.0f) << v;
        EXPECT_EQ(quad.joints[v * 4 + 1], top ? 1u : 0u) << v;
        EXPECT_FLOAT_EQ(quad.weights[v * 4 + 1], top ? 0.5f : 0.0f) << v;
    }
    // Bend: ticks 0 and 10 at 10 per second are 0 s and 1 s.
    ASSERT_EQ(model.animations.size(), 1u);
    EXPECT_EQ(model.animations[0].name, "Bend");
    bool rotation = false;
    for (const AnimationChannel& channel : model.animations[0].channels)
    {
        EXPECT_EQ(channel.node, 2);
        if (channel.path != AnimationPath::Rotation) continue;
        rotation = true;
        EXPECT_EQ(channel.interpolation, KeyInterpolation::Linear);
        EXPECT_EQ(channel.times, (std::vector<double>{0.0, 1.0}));
        EXPECT_NEAR(std::abs(channel.values[1].w), std::sqrt(0.5), 1e-6); // a quarter turn
    }
    EXPECT_TRUE(rotation);
}

TEST(AssimpReader, ReadsFromMemoryAsFromAFile)
{
    const std::string text = chainText();
    const RiggedModelRead read = readAssimpMemory(text.data(), text.size(), "x", "memory.x");
    ASSERT_TRUE(read) << read.error;
    EXPECT_EQ(read.model->sourceFile, "memory.x");
    EXPECT_EQ(read.model->skins.size(), 1u);
    const RiggedModelRead bad = readAssimpMemory(text.data(), 40, "x", "short.x");
    EXPECT_FALSE(bad.model);
    EXPECT_EQ(bad.error.rfind("short.x: Assimp cannot read it", 0), 0u) << bad.error;
}

TEST(AssimpReader, AssumesTwentyFiveTicksPerSecondWhereTheFileGivesNone)
{
    const RiggedModelRead read = readChanged(writeChain("chain_ticks.x"), [](aiScene& scene) {
        scene.mAnimations[0]->mTicksPerSecond = 0.0;
    });
    ASSERT_TRUE(read) << read.error;
    EXPECT_TRUE(anyWarningSays(read.warnings, "changed.assbin: animations[0] 'Bend': the file gives no ticks per second; 25 are assumed"));
    for (const AnimationChannel& channel : read.model->animations[0].channels)
        if (channel.path == AnimationPath::Rotation)
        {
            EXPECT_EQ(channel.times, (std::vector<double>{0.0, 0.4}));
        }
}

TEST(AssimpReader, MovesKeysBeforeTimeZeroToStartAtZero)
{
    const RiggedModelRead read = readChanged(writeChain("chain_negative.x"), [](aiScene& scene) {
        aiNodeAnim& channel = *scene.mAnimations[0]->mChannels[0];
        for (unsigned k = 0; k < channel.mNumRotationKeys; ++k) channel.mRotationKeys[k].mTime -= 5.0;
        for (unsigned k = 0; k < channel.mNumPositionKeys; ++k) channel.mPositionKeys[k].mTime -= 5.0;
        for (unsigned k = 0; k < channel.mNumScalingKeys; ++k) channel.mScalingKeys[k].mTime -= 5.0;
    });
    ASSERT_TRUE(read) << read.error;
    EXPECT_TRUE(anyWarningSays(read.warnings, "its keys start at -0.5"));
    for (const AnimationChannel& channel : read.model->animations[0].channels)
        if (channel.path == AnimationPath::Rotation)
        {
            EXPECT_EQ(channel.times, (std::vector<double>{0.0, 1.0}));
        }
}

TEST(AssimpReader, WarnsAboutMorphTargetsMeshChannelsAndAnimatedScaleAndReadsTheRest)
{
    // The chain's scene with a morph target on its mesh, a morph channel, and Lower scaled from 1 to 2 over the
    // bend: the morphs are left out by the reader, the scale by the mapping, each with a warning; the bend is kept.
    Assimp::Importer importer;
    ASSERT_TRUE(importer.ReadFile(writeChain("chain_morph.x"), 0)) << importer.GetErrorString();
    std::unique_ptr<aiScene> scene(importer.GetOrphanedScene());
    aiMesh& mesh = *scene->mMeshes[0]; // a vertex per face corner: no post-processing joins them
    mesh.mNumAnimMeshes = 1;
    mesh.mAnimMeshes = new aiAnimMesh*[1]{new aiAnimMesh};
    mesh.mAnimMeshes[0]->mNumVertices = mesh.mNumVertices;
    mesh.mAnimMeshes[0]->mVertices = new aiVector3D[mesh.mNumVertices];
    aiAnimation& bend = *scene->mAnimations[0];
    bend.mNumMorphMeshChannels = 1;
    bend.mMorphMeshChannels = new aiMeshMorphAnim*[1]{new aiMeshMorphAnim};
    aiNodeAnim& lower = *bend.mChannels[0];
    delete[] lower.mScalingKeys;
    lower.mNumScalingKeys = 2;
    lower.mScalingKeys = new aiVectorKey[2]{aiVectorKey(0.0, aiVector3D(1.0f)), aiVectorKey(10.0, aiVector3D(2.0f))};

    const RiggedModelRead read = assimp::readScene(*scene, "morph.x", std::string());
    ASSERT_TRUE(read) << read.error;
    EXPECT_TRUE(anyWarningSays(read.warnings, "morph.x: meshes[0] 'Root': 1 morph targets are left out"));
    EXPECT_TRUE(anyWarningSays(read.warnings, "morph.x: animations[0] 'Bend': its mesh and morph channels are left out"));
    EXPECT_EQ(read.model->meshes[0].primitives[0].getNumVertices(), std::size_t(mesh.mNumVertices));
    const RiggedActor actor = buildRiggedActor(read.model);
    ASSERT_TRUE(actor) << actor.error;
    EXPECT_TRUE(anyWarningSays(actor.warnings, "animations[0] 'Bend': the scale of nodes[2] 'Lower' is animated"))
        << actor.warnings.size();
    ASSERT_EQ(actor.clips.size(), 1u);
    EXPECT_GE(actor.clips[0]->findChannel("Lower.rx"), 0);
}

TEST(AssimpReader, ReadsDirectXCharactersWithSeveralSkinsAndAnimations)
{
    const RiggedModelRead bcn = readAssimpFile(assimpModels("X/BCN_Epileptic.X"));
    ASSERT_TRUE(bcn) << bcn.error;
    EXPECT_EQ(bcn.model->skins.size(), 3u); // Torso, Head, Legs
    std::size_t bones = 0;
    for (const RiggedSkin& skin : bcn.model->skins) bones += skin.joints.size();
    EXPECT_EQ(bones, 24u + 20u + 10u);
    const RiggedModelRead wuson = readAssimpFile(assimpModels("X/Testwuson.X"));
    ASSERT_TRUE(wuson) << wuson.error;
    ASSERT_EQ(wuson.model->animations.size(), 3u);
    EXPECT_EQ(wuson.model->animations[0].name, "Wuson_Run");
    EXPECT_EQ(wuson.model->animations[1].name, "Wuson_Walk");
    EXPECT_EQ(wuson.model->animations[2].name, "Wuson_Bind");
    double first, last;
    animationTimeRange(wuson.model->animations[0], first, last);
    EXPECT_DOUBLE_EQ(last, 4640.0 / 4800.0); // ticks over the file's 4800 per second
    const RiggedActor actor = buildRiggedActor(wuson.model);
    ASSERT_TRUE(actor) << actor.error;
    EXPECT_EQ(actor.clips.size(), 3u);
}

TEST(AssimpReader, ReadsFbxArmaturesInTheFilesCentimetres)
{
    const RiggedModelRead read = readAssimpFile(assimpModels("FBX/huesitos.fbx"));
    ASSERT_TRUE(read) << read.error;
    const RiggedModel& model = *read.model;
    EXPECT_EQ(model.nodes[0].name, "RootNode");
    // Blender's armature keeps its metres under a scale of 100 into the file's centimetres; nothing converts them.
    EXPECT_EQ(model.nodes[1].name, "Armature");
    EXPECT_NEAR(model.nodes[1].scale.x, 100.0, 1e-3);
    ASSERT_EQ(model.animations.size(), 1u);
    EXPECT_EQ(model.animations[0].name, "Armature|Action");
    double first, last;
    animationTimeRange(model.animations[0], first, last);
    EXPECT_DOUBLE_EQ(last, 39.0 / 25.0);
    EXPECT_TRUE(anyWarningSays(read.warnings, "1 cameras are left out"));
}

TEST(AssimpReader, FoldsFbxPivotsIntoTheirNodes)
{
    const RiggedModelRead read = readAssimpFile(assimpModels("FBX/cubes_with_mirroring_and_pivot.fbx"));
    ASSERT_TRUE(read) << read.error;
    for (const RiggedNode& node : read.model->nodes)
        EXPECT_EQ(node.name.find("$AssimpFbx$"), std::string::npos) << node.name;
    EXPECT_EQ(read.model->meshes.size(), 4u);
}

TEST(AssimpReader, GivesEachFurtherMeshOfANodeAChildNode)
{
    // kwxport's cube: one node drawing three meshes (one per material).
    const RiggedModelRead read = readAssimpFile(assimpModels("X/kwxport_test_cubewithvcolors.x"));
    ASSERT_TRUE(read) << read.error;
    const RiggedModel& model = *read.model;
    ASSERT_EQ(model.nodes.size(), 3u);
    EXPECT_EQ(model.nodes[0].mesh, 0);
    EXPECT_EQ(model.nodes[1].parent, 0);
    EXPECT_EQ(model.nodes[1].mesh, 1);
    EXPECT_EQ(model.nodes[1].name, "Box01/Box01");
    EXPECT_EQ(model.nodes[2].mesh, 2);
    EXPECT_EQ(model.nodes[1].translation, glm::dvec3(0.0));
}

TEST(AssimpReader, FindsTexturesBesideTheModelEmbeddedOrMissing)
{
    // duck.dae names ./duckCM.tga; kwxport's cube names Windows paths of another machine, found by their file name
    // beside the model; duck.zae and an FBX carry theirs inside; spider.fbx's are nowhere.
    const RiggedModelRead duck = readAssimpFile(assimpModels("Collada/duck.dae"));
    ASSERT_TRUE(duck) << duck.error;
    ASSERT_EQ(duck.model->images.size(), 1u);
    EXPECT_EQ(duck.model->images[0].uri, "./duckCM.tga");
    EXPECT_EQ(duck.model->images[0].width, 512u);
    EXPECT_EQ(duck.model->images[0].rgba.size(), 512u * 512u * 4u);
    EXPECT_EQ(duck.model->materials[0].name, "blinn3");
    EXPECT_EQ(duck.model->materials[0].baseColorTexture.image, 0);
    const RiggedModelRead cube = readAssimpFile(assimpModels("X/kwxport_test_cubewithvcolors.x"));
    ASSERT_TRUE(cube) << cube.error;
    EXPECT_EQ(cube.model->images.size(), 3u);
    for (const char* file : {"Collada/duck.zae", "FBX/box_orphant_embedded_texture.fbx"})
    {
        const RiggedModelRead embedded = readAssimpFile(assimpModels(file));
        ASSERT_TRUE(embedded) << embedded.error;
        ASSERT_EQ(embedded.model->images.size(), 1u) << file;
        EXPECT_TRUE(embedded.model->images[0].uri.empty()) << file;
        EXPECT_GT(embedded.model->images[0].width, 0u) << file;
    }
    const RiggedModelRead spider = readAssimpFile(assimpModels("FBX/spider.fbx"));
    ASSERT_TRUE(spider) << spider.error;
    EXPECT_TRUE(spider.model->images.empty());
    EXPECT_TRUE(anyWarningSays(spider.warnings, "materials[1] 'Skin': its texture 'D:\\projects\\assimp_int\\test\\models\\OBJ\\wal67ar_small.jpg' is not found; it is drawn untextured"));
}

TEST(AssimpReader, ReadRiggedModelFileTakesAssimpsFormatsByTheirExtension)
{
    for (const char* name : {"hero.dae", "hero.ZAE", "hero.fbx", "hero.X", "hero.md5mesh", "hero.smd"})
        EXPECT_TRUE(isRiggedModelFile(name)) << name;
    EXPECT_FALSE(isAssimpModelFile("walk.bvh")); // read exactly by osgActor's own BVH reader
    EXPECT_FALSE(isAssimpModelFile("hero.gltf"));
    const RiggedModelRead read = readRiggedModelFile(assimpModels("FBX/huesitos.fbx"));
    ASSERT_TRUE(read) << read.error;
    EXPECT_EQ(read.model->skins.size(), 1u);
}
