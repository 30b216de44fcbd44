// The glTF reader refuses broken files with the file and the place, and gives no model: real broken files from
// Debian's assimp-testmodels, and files written here with one thing wrong each.
#include "GltfTestFile"
#include "ImportTestUtil"

#include <osgActor/import/GltfReader>

#include <gtest/gtest.h>

#include <fstream>
#include <iterator>

using namespace osgActor;
using namespace osgActor::test;

namespace {

::testing::AssertionResult refused(const RiggedModelRead& read, const std::string& fileAndPlace, const std::string& what)
{
    if (read.model) return ::testing::AssertionFailure() << "a model was read";
    if (read.error.compare(0, fileAndPlace.size(), fileAndPlace) != 0)
        return ::testing::AssertionFailure() << "the error '" << read.error << "' does not start with '" << fileAndPlace << "'";
    if (read.error.find(what) == std::string::npos)
        return ::testing::AssertionFailure() << "the error '" << read.error << "' does not say '" << what << "'";
    return ::testing::AssertionSuccess();
}

/** A skinned two-joint strip with one LINEAR rotation channel, the base the refusal tests break one thing of. */
struct SkinnedStrip
{
    GltfTestFile file;
    int positions, joints, weights, indices, inverseBind, times, rotations;
    SkinnedStrip(std::vector<float> weightValues = {1, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0},
                 std::vector<std::uint16_t> indexValues = {0, 1, 2},
                 std::vector<float> timeValues = {0, 1})
    {
        positions = file.addFloats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
        joints = file.addUShorts({0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0}, "VEC4");
        weights = file.addFloats(weightValues, "VEC4");
        indices = file.addUShorts(indexValues, "SCALAR");
        inverseBind = file.addFloats({1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1,
                                      1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, -1, 0, 1}, "MAT4");
        times = file.addFloats(timeValues, "SCALAR");
        rotations = file.addFloats({0, 0, 0, 1, 0, 0, 0.7071068f, 0.7071068f}, "VEC4");
    }
    std::string body(const std::string& skinJoints = "[1,2]", const std::string& nodes =
                         R"([{"mesh":0,"skin":0},{"children":[2]},{"translation":[0,1,0]}])") const
    {
        const auto n = [](int i) { return std::to_string(i); };
        return R"("scene":0,"scenes":[{"nodes":[0,1]}],"nodes":)" + nodes +
               R"(,"meshes":[{"primitives":[{"attributes":{"POSITION":)" + n(positions) + R"(,"JOINTS_0":)" + n(joints) +
               R"(,"WEIGHTS_0":)" + n(weights) + R"(},"indices":)" + n(indices) + R"(}]}],"skins":[{"joints":)" +
               skinJoints + R"(,"inverseBindMatrices":)" + n(inverseBind) +
               R"(}],"animations":[{"channels":[{"sampler":0,"target":{"node":2,"path":"rotation"}}],"samplers":[{"input":)" +
               n(times) + R"(,"output":)" + n(rotations) + R"(}]}])";
    }
    RiggedModelRead read(const std::string& name, const std::string& body) const
    {
        file.write(written(name), body);
        return readGltfFile(written(name));
    }
    /** Reads the file with the text from "before" (the first after "buffers" when inBuffers) up to the next comma
      * replaced by "after". */
    RiggedModelRead readEdited(const std::string& name, const std::string& before, const std::string& after,
                               bool inBuffers = false) const
    {
        std::string json = file.json(body());
        const std::size_t at = json.find(before, inBuffers ? json.find("\"buffers\"") : 0);
        json.replace(at, json.find(',', at) - at, after);
        std::ofstream(written(name)) << json;
        return readGltfFile(written(name));
    }
};

} // namespace

TEST(GltfReaderRefuses, AFileThatDoesNotExist)
{
    EXPECT_TRUE(refused(readGltfFile(written("no_such_file.gltf")), written("no_such_file.gltf") + ": ", "cannot open"));
}

TEST(GltfReaderRefuses, AMissingBufferFile)
{
    const std::string path = gltf2("MissingBin/BoxTextured.gltf");
    EXPECT_TRUE(refused(readGltfFile(path), path + ": ", "BoxTextured0.bin"));
}

TEST(GltfReaderRefuses, IndicesOutOfRangeNamingThePrimitive)
{
    const std::string path = gltf2("IndexOutOfRange/IndexOutOfRange.gltf");
    EXPECT_TRUE(refused(readGltfFile(path), path + ": meshes[0].primitives[0]: ", "out of range (24 vertices)"));
    const std::string all = gltf2("IndexOutOfRange/AllIndicesOutOfRange.gltf");
    EXPECT_TRUE(refused(readGltfFile(all), all + ": meshes[0].primitives[0]: ", "out of range"));
}

TEST(GltfReaderRefuses, ANodeHierarchyWithACycle)
{
    const std::string path = gltf2("RecursiveNodes/RecursiveNodes.gltf");
    EXPECT_TRUE(refused(readGltfFile(path), path + ": nodes[", "cycle"));
}

TEST(GltfReaderRefuses, InfiniteNumbersInAnAccessor)
{
    const std::string path = gltf2("BoxWithInfinites-glTF-Binary/BoxWithInfinites.glb");
    EXPECT_TRUE(refused(readGltfFile(path), path + ": accessors[", "not finite"));
}

TEST(GltfReaderRefuses, AMeshWhosePrimitivesAreNotAList)
{
    // assimp's wrongTypes/badArray: "primitives" is an object, which tinygltf reads as no primitives.
    const std::string path = gltf2("wrongTypes/badArray.gltf");
    EXPECT_TRUE(refused(readGltfFile(path), path + ": meshes[0]: ", "has no primitives"));
}

TEST(GltfReaderRefuses, NothingOfTheOtherWrongTypesButReadsThemWithTheDefaults)
{
    // assimp's other wrongTypes files: a name that is a number, a texture scale that is a string, a material part
    // that is a list, a texture index of -1. tinygltf ignores what has the wrong type; the box still reads, with
    // the default for each ignored value.
    for (const char* name : {"badExtension", "badNumber", "badObject", "badString", "badUint"})
    {
        const std::string path = gltf2(std::string("wrongTypes/") + name + ".gltf");
        const RiggedModelRead read = readGltfFile(path);
        ASSERT_TRUE(read.model) << read.error;
        EXPECT_EQ(read.model->meshes.at(0).primitives.at(0).indices.size(), 36u) << name;
    }
    const RiggedModelRead badUint = readGltfFile(gltf2("wrongTypes/badUint.gltf"));
    EXPECT_EQ(badUint.model->materials.at(0).baseColorTexture.image, -1); // "index": -1, no texture
}

TEST(GltfReaderRefuses, ATruncatedGlb)
{
    std::ifstream in(gltf2("BoxTextured-glTF-Binary/BoxTextured.glb"), std::ios::binary);
    std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    ASSERT_GT(bytes.size(), 2000u);
    for (std::size_t keep : {std::size_t(3), std::size_t(20), bytes.size() / 2, bytes.size() - 1})
    {
        const std::string path = written("truncated.glb");
        std::ofstream(path, std::ios::binary).write(bytes.data(), std::streamsize(keep));
        const RiggedModelRead read = readGltfFile(path);
        EXPECT_FALSE(read.model) << keep << " bytes";
        EXPECT_EQ(read.error.compare(0, path.size() + 2, path + ": "), 0) << read.error;
    }
}

TEST(GltfReaderRefuses, AShortEmbeddedBuffer)
{
    // The buffer claims more bytes than its data URI holds.
    const SkinnedStrip strip;
    EXPECT_TRUE(refused(strip.readEdited("short_buffer.gltf", "\"byteLength\":", "\"byteLength\":100000", true),
                        written("short_buffer.gltf") + ": ", ""));
}

TEST(GltfReaderRefuses, WeightsThatSumToZero)
{
    SkinnedStrip strip({1, 0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0});
    EXPECT_TRUE(refused(strip.read("zero_weights.gltf", strip.body()), written("zero_weights.gltf") +
                        ": meshes[0].primitives[0]: ", "vertex 1's weights sum to zero"));
}

TEST(GltfReaderRefuses, ANaNInAnAccessor)
{
    SkinnedStrip strip({1, 0, 0, 0, std::nanf(""), 0, 0, 0, 0, 1, 0, 0});
    EXPECT_TRUE(refused(strip.read("nan_weight.gltf", strip.body()), written("nan_weight.gltf") + ": accessors[2] (WEIGHTS of meshes[0].primitives[0]): ",
                        "element 1 holds a number that is not finite"));
}

TEST(GltfReaderRefuses, ASkinJointThatIsNotANode)
{
    SkinnedStrip strip;
    EXPECT_TRUE(refused(strip.read("bad_joint.gltf", strip.body("[1,7]")), written("bad_joint.gltf") + ": skins[0]: ",
                        "joints[1] = 7 is not a node"));
}

TEST(GltfReaderRefuses, AVertexNamingAJointTheSkinDoesNotHave)
{
    SkinnedStrip strip;
    EXPECT_TRUE(refused(strip.read("joint_number.gltf", strip.body("[1]")),
                        written("joint_number.gltf") + ": meshes[0].primitives[0]: ",
                        "vertex 2 names joint 1 but skins[0] has 1 joints"));
}

TEST(GltfReaderRefuses, ANodeWithTwoParents)
{
    SkinnedStrip strip;
    EXPECT_TRUE(refused(strip.read("two_parents.gltf",
                                   strip.body("[1,2]", R"([{"mesh":0,"skin":0,"children":[2]},{"children":[2]},{}])")),
                        written("two_parents.gltf") + ": nodes[2]: ", "is a child of both nodes[0] and nodes[1]"));
}

TEST(GltfReaderRefuses, KeyTimesThatDoNotIncrease)
{
    SkinnedStrip strip({1, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0}, {0, 1, 2}, {1, 1});
    EXPECT_TRUE(refused(strip.read("times.gltf", strip.body()),
                        written("times.gltf") + ": accessors[5] (input of animations[0].samplers[0]): ",
                        "not strictly increasing at key 1"));
}

TEST(GltfReaderRefuses, AnIndexCountThatIsNotWholeTriangles)
{
    SkinnedStrip strip({1, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0}, {0, 1});
    EXPECT_TRUE(refused(strip.read("two_indices.gltf", strip.body()),
                        written("two_indices.gltf") + ": meshes[0].primitives[0]: ", "not a whole number of triangles"));
}

TEST(GltfReaderRefuses, AnAccessorThatReachesPastItsBufferView)
{
    // The positions accessor claims 30 vertices over a 36-byte view.
    const SkinnedStrip strip;
    EXPECT_TRUE(refused(strip.readEdited("long_accessor.gltf", "\"count\":3,", "\"count\":30"),
                        written("long_accessor.gltf") + ": accessors[0] (POSITION of meshes[0].primitives[0]): ",
                        "reach past the end of bufferViews[0]"));
}

TEST(GltfReaderRefuses, NothingWorseThanAnErrorForAnyCorruptedByteOfAGlb)
{
    // Every seventeenth byte of the .glb (header, JSON, binary chunk) replaced in turn, by 0 and by 255: each read gives a
    // model or an error naming the file, never a crash (the sanitizer build checks every access).
    std::ifstream in(gltf2("BoxTextured-glTF-Binary/BoxTextured.glb"), std::ios::binary);
    const std::vector<char> original((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    ASSERT_GT(original.size(), 1000u);
    const std::string path = written("corrupted.glb");
    unsigned refusals = 0;
    for (std::size_t i = 0; i < original.size(); i += 17)
        for (char replacement : {'\0', '\xff'})
        {
            std::vector<char> bytes = original;
            bytes[i] = replacement;
            std::ofstream(path, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
            const RiggedModelRead read = readGltfFile(path);
            if (read.model) continue;
            ++refusals;
            ASSERT_EQ(read.error.compare(0, path.size() + 2, path + ": "), 0) << "byte " << i << ": " << read.error;
        }
    EXPECT_GT(refusals, 0u);
}
