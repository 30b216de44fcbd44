// The glTF reader on real files: Khronos's Cesium Man (committed), Debian's assimp-testmodels (textured boxes in
// .gltf, .glb and embedded form, a simple skin, cameras, morph targets, an extension).
#include "ImportTestUtil"
#include "ReferenceGltf"
#include "TestMath"

#include <osgActor/import/GltfReader>
#include <osgActor/import/RiggedModelFile>

#include <gtest/gtest.h>

#include <cstdint>
#include <fstream>
#include <iterator>

#include <glm/gtc/quaternion.hpp>

using namespace osgActor;
using namespace osgActor::test;

namespace {


} // namespace

TEST(RiggedModelFile, RefusesAnExtensionItDoesNotRead)
{
    const RiggedModelRead read = readRiggedModelFile("hero.obj");
    EXPECT_FALSE(read.model);
    EXPECT_EQ(read.error, "hero.obj: not a rigged model file osgActor reads (expected .gltf, .glb, .dae, .fbx, .x, .osgt, ...)");
    EXPECT_TRUE(isRiggedModelFile("a/b/Hero.GLB"));
    EXPECT_TRUE(isRiggedModelFile("hero.gltf"));
    EXPECT_FALSE(isRiggedModelFile("hero.gltf.actor"));
}

TEST(GltfReader, ReadsCesiumManWhole)
{
    const RiggedModelRead read = readGltfFile(cesiumMan());
    ASSERT_TRUE(read.model) << read.error;
    EXPECT_TRUE(read.warnings.empty()) << read.warnings.front();
    const RiggedModel& model = *read.model;
    ASSERT_EQ(model.nodes.size(), 22u);
    EXPECT_EQ(model.nodes[0].name, "Z_UP");
    EXPECT_EQ(model.nodes[3].name, "Skeleton_torso_joint_1");
    EXPECT_EQ(model.nodes[3].parent, 1);
    EXPECT_EQ(model.sceneRoots, std::vector<int>{0});
    // Z_UP's matrix (columns (1,0,0), (0,0,-1), (0,1,0): -90 degrees about X) decomposed into a rotation.
    EXPECT_TRUE(vectorsNear(model.nodes[0].rotation * glm::dvec3(0, 1, 0), glm::dvec3(0, 0, -1), 1e-15));
    EXPECT_TRUE(vectorsNear(model.nodes[0].rotation * glm::dvec3(0, 0, 1), glm::dvec3(0, 1, 0), 1e-15));
    EXPECT_TRUE(vectorsNear(model.nodes[0].scale, glm::dvec3(1.0), 1e-15));

    ASSERT_EQ(model.meshes.size(), 1u);
    const RiggedPrimitive& body = model.meshes[0].primitives.at(0);
    EXPECT_EQ(body.place, "meshes[0].primitives[0]");
    EXPECT_EQ(body.positions.size(), 3273u);
    EXPECT_EQ(body.normals.size(), 3273u);
    EXPECT_EQ(body.texCoords0.size(), 3273u);
    EXPECT_TRUE(body.tangents.empty());
    EXPECT_EQ(body.indices.size(), 14016u);
    EXPECT_EQ(body.influencesPerVertex, 4u);
    EXPECT_EQ(body.joints.size(), 4u * 3273u);
    EXPECT_EQ(body.material, 0);

    ASSERT_EQ(model.skins.size(), 1u);
    EXPECT_EQ(model.skins[0].joints.size(), 19u);
    EXPECT_EQ(model.skins[0].inverseBindMatrices.size(), 19u);
    EXPECT_EQ(model.nodes[2].skin, 0);
    EXPECT_EQ(model.nodes[2].mesh, 0);

    ASSERT_EQ(model.materials.size(), 1u);
    EXPECT_EQ(model.materials[0].baseColorFactor, glm::dvec4(1.0));
    EXPECT_EQ(model.materials[0].baseColorTexture.image, 0);
    EXPECT_EQ(model.materials[0].baseColorTexture.minFilter, TextureFilter::NearestMipmapLinear); // 9986
    ASSERT_EQ(model.images.size(), 1u);
    EXPECT_EQ(model.images[0].uri, "CesiumMan_img0.jpg");
    EXPECT_EQ(model.images[0].width, 1024u);
    EXPECT_EQ(model.images[0].height, 1024u);
    EXPECT_EQ(model.images[0].rgba.size(), 1024u * 1024u * 4u);

    ASSERT_EQ(model.animations.size(), 1u);
    EXPECT_EQ(model.animations[0].name, "animation0");
    EXPECT_EQ(model.animations[0].channels.size(), 57u);
    const AnimationChannel& first = model.animations[0].channels[0];
    EXPECT_EQ(first.node, 3);
    EXPECT_EQ(first.path, AnimationPath::Translation);
    EXPECT_EQ(first.interpolation, KeyInterpolation::Linear);
    EXPECT_EQ(first.times.size(), 48u);
    EXPECT_NEAR(first.times.back(), 2.0, 1e-7);
}

TEST(GltfReader, GivesTheDataTheFileHolds)
{
    // Every vertex position, weight and inverse bind matrix of Cesium Man equals the reference decoder's.
    const RiggedModelRead read = readGltfFile(cesiumMan());
    ASSERT_TRUE(read.model) << read.error;
    const ReferenceGltf reference(cesiumMan());
    ASSERT_TRUE(reference.loaded);
    const tinygltf::Primitive& primitive = reference.model.meshes[0].primitives[0];
    const std::vector<double> positions = reference.floats(primitive.attributes.at("POSITION"));
    const std::vector<double> weights = reference.floats(primitive.attributes.at("WEIGHTS_0"));
    const RiggedPrimitive& body = read.model->meshes[0].primitives[0];
    for (std::size_t v = 0; v < body.positions.size(); ++v)
        for (int c = 0; c < 3; ++c) ASSERT_EQ(double(body.positions[v][c]), positions[3 * v + c]) << v;
    for (std::size_t i = 0; i < body.weights.size(); ++i) ASSERT_EQ(double(body.weights[i]), weights[i]) << i;
    const std::vector<double> inverseBind = reference.floats(reference.model.skins[0].inverseBindMatrices);
    for (std::size_t j = 0; j < 19; ++j)
        for (int i = 0; i < 16; ++i)
            ASSERT_EQ(read.model->skins[0].inverseBindMatrices[j][i / 4][i % 4], inverseBind[16 * j + i]);
}

TEST(GltfReader, ReadsTheSameBoxFromGltfGlbAndEmbeddedFiles)
{
    const RiggedModelRead separate = readGltfFile(gltf2("BoxTextured-glTF/BoxTextured.gltf"));
    const RiggedModelRead binary = readGltfFile(gltf2("BoxTextured-glTF-Binary/BoxTextured.glb"));
    const RiggedModelRead embedded = readGltfFile(gltf2("BoxTextured-glTF-Embedded/BoxTextured.gltf"));
    ASSERT_TRUE(separate.model) << separate.error;
    ASSERT_TRUE(binary.model) << binary.error;
    ASSERT_TRUE(embedded.model) << embedded.error;
    for (const RiggedModelRead* read : {&binary, &embedded})
    {
        const RiggedPrimitive& a = separate.model->meshes[0].primitives[0];
        const RiggedPrimitive& b = read->model->meshes[0].primitives[0];
        EXPECT_EQ(a.positions, b.positions);
        EXPECT_EQ(a.normals, b.normals);
        EXPECT_EQ(a.texCoords0, b.texCoords0);
        EXPECT_EQ(a.indices, b.indices);
        EXPECT_EQ(separate.model->images[0].rgba, read->model->images[0].rgba);
    }
    const RiggedModel& box = *separate.model;
    EXPECT_EQ(box.meshes[0].primitives[0].positions.size(), 24u);
    EXPECT_EQ(box.meshes[0].primitives[0].indices.size(), 36u);
    EXPECT_EQ(box.images[0].width, 211u); // CesiumLogoFlat.png, 211 x 211
    EXPECT_EQ(box.images[0].height, 211u);
    // The sampler: MIRRORED_REPEAT on S, CLAMP_TO_EDGE on T, NEAREST_MIPMAP_LINEAR (9986), LINEAR.
    const RiggedTexture& texture = box.materials[0].baseColorTexture;
    EXPECT_EQ(texture.wrapS, TextureWrap::MirroredRepeat);
    EXPECT_EQ(texture.wrapT, TextureWrap::ClampToEdge);
    EXPECT_EQ(texture.minFilter, TextureFilter::NearestMipmapLinear);
    EXPECT_EQ(texture.magFilter, TextureFilter::Linear);
}

TEST(GltfReader, ReadsASimpleSkinWithoutNamesOrMaterials)
{
    const RiggedModelRead read = readGltfFile(gltf2("simple_skin/simple_skin.gltf"));
    ASSERT_TRUE(read.model) << read.error;
    const RiggedModel& model = *read.model;
    EXPECT_EQ(model.nodes[0].name, "node0");
    EXPECT_EQ(model.nodes[2].name, "node2");
    EXPECT_EQ(model.nodes[2].parent, 1);
    EXPECT_EQ(model.skins[0].joints, (std::vector<int>{1, 2}));
    EXPECT_TRUE(matricesNear(model.skins[0].inverseBindMatrices[1],
                             glm::dmat4(1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, -0.5, -1, 0, 1)));
    EXPECT_EQ(model.meshes[0].primitives[0].material, -1);
    EXPECT_EQ(model.animations[0].channels[0].times.size(), 12u);
}

TEST(GltfReader, WarnsAboutCamerasMorphTargetsAndExtensionsAndReadsTheRest)
{
    const RiggedModelRead cameras = readGltfFile(gltf2("cameras/Cameras.gltf"));
    ASSERT_TRUE(cameras.model) << cameras.error;
    EXPECT_TRUE(anyWarningSays(cameras.warnings, "2 cameras are left out"));
    EXPECT_EQ(cameras.model->meshes.size(), 1u);

    const RiggedModelRead morph = readGltfFile(gltf2("glTF-Sample-Models/AnimatedMorphCube-glTF/AnimatedMorphCube.gltf"));
    ASSERT_TRUE(morph.model) << morph.error;
    EXPECT_TRUE(anyWarningSays(morph.warnings, "meshes[0].primitives[0]: 2 morph targets are left out"));
    EXPECT_TRUE(anyWarningSays(morph.warnings, "animations[0]: morph target weights are not animated"));
    EXPECT_EQ(morph.model->meshes[0].primitives[0].positions.size(), 24u);

    const std::string path = gltf2("textureTransform/TextureTransformTest.gltf");
    const RiggedModelRead transform = readGltfFile(path);
    ASSERT_TRUE(transform.model) << transform.error;
    EXPECT_TRUE(anyWarningSays(transform.warnings, path + ": extension KHR_texture_transform is not supported"));
}

// tinygltf trusts a GLB chunk's length and copied past the end of the input when a chunk claimed more bytes than the
// file holds (found by fuzz_gltf): the framing is checked first and such a file refused with the chunk and its place.
TEST(GltfReader, RefusesAGlbWhoseChunkRunsPastTheEndOrWhoseLengthIsWrong)
{
    std::ifstream in(gltf2("BoxTextured-glTF-Binary/BoxTextured.glb"), std::ios::binary);
    const std::string glb((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    ASSERT_GT(glb.size(), 28u);
    const auto wordAt = [](const std::string& bytes, std::size_t at) {
        return std::uint32_t(std::uint8_t(bytes[at])) | std::uint32_t(std::uint8_t(bytes[at + 1])) << 8 |
               std::uint32_t(std::uint8_t(bytes[at + 2])) << 16 | std::uint32_t(std::uint8_t(bytes[at + 3])) << 24;
    };
    const std::size_t binAt = 20 + wordAt(glb, 12); // after the header and the JSON chunk
    const std::uint32_t binLength = wordAt(glb, binAt);
    ASSERT_EQ(binAt + 8 + binLength, glb.size());

    std::string overlong = glb;
    const std::uint32_t claimed = binLength + 6;
    for (int b = 0; b < 4; ++b) overlong[binAt + b] = char((claimed >> (8 * b)) & 0xff);
    const std::string expected = "GLB chunk 1 at byte " + std::to_string(binAt) + " claims " + std::to_string(claimed) +
                                 " bytes; " + std::to_string(binLength) + " remain in the file";
    const RiggedModelRead fromMemory = readGltfMemory(overlong.data(), overlong.size(), "box.glb");
    EXPECT_FALSE(fromMemory.model);
    EXPECT_EQ(fromMemory.error, "box.glb: " + expected);
    const std::string path = ::testing::TempDir() + "overlong_chunk.glb";
    std::ofstream(path, std::ios::binary) << overlong;
    const RiggedModelRead fromFile = readGltfFile(path);
    EXPECT_FALSE(fromFile.model);
    EXPECT_EQ(fromFile.error, path + ": " + expected);

    const std::string truncated = glb.substr(0, glb.size() - 4);
    const RiggedModelRead cut = readGltfMemory(truncated.data(), truncated.size(), "cut.glb");
    EXPECT_FALSE(cut.model);
    EXPECT_EQ(cut.error, "cut.glb: the GLB header gives a length of " + std::to_string(glb.size()) +
                             " bytes; the file has " + std::to_string(truncated.size()));
}

TEST(GltfReader, ReadsFromMemoryAsFromAFileButNoFileItNames)
{
    const auto bytesOf = [](const std::string& path) {
        std::ifstream in(path, std::ios::binary);
        return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    };
    const std::string glb = bytesOf(gltf2("BoxTextured-glTF-Binary/BoxTextured.glb"));
    const RiggedModelRead fromMemory = readGltfMemory(glb.data(), glb.size(), "box.glb");
    const RiggedModelRead fromFile = readGltfFile(gltf2("BoxTextured-glTF-Binary/BoxTextured.glb"));
    ASSERT_TRUE(fromMemory) << fromMemory.error;
    ASSERT_TRUE(fromFile) << fromFile.error;
    EXPECT_EQ(fromMemory.model->sourceFile, "box.glb");
    EXPECT_EQ(fromMemory.model->nodes.size(), fromFile.model->nodes.size());
    EXPECT_EQ(fromMemory.model->meshes[0].primitives[0].positions, fromFile.model->meshes[0].primitives[0].positions);
    EXPECT_EQ(fromMemory.model->images[0].rgba, fromFile.model->images[0].rgba); // embedded in the .glb
    // The .gltf's buffer is a file beside it: not read from memory.
    const std::string text = bytesOf(gltf2("BoxTextured-glTF/BoxTextured.gltf"));
    const RiggedModelRead external = readGltfMemory(text.data(), text.size(), "box.gltf");
    EXPECT_FALSE(external.model);
    EXPECT_EQ(external.error.rfind("box.gltf: ", 0), 0u) << external.error;
    EXPECT_NE(external.error.find("is not read (the model was read from memory)"), std::string::npos) << external.error;
}
