// Serialization: a skinned actor written to .osgt and .osgb and read back has its skins inline and equal, draws and
// deforms as before, and writes back the same bytes; a broken skin fails the read with SkinBuilder's message.
#include "SkinDrawTestUtil"

#include <osgDB/ReadFile>
#include <osgDB/Registry>
#include <osgDB/WriteFile>

#include <gtest/gtest.h>

#include <cctype>
#include <fstream>
#include <sstream>

using namespace osgActor;
using namespace osgActor::test;

namespace {

std::string written(const std::string& name) { return std::string(OSGACTOR_TEST_BINARY_DIR) + "/" + name; }

std::string contentsOf(const std::string& file)
{
    std::ifstream in(file, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

osg::ref_ptr<osg::Node> writeAndReadBack(osg::Node& node, const std::string& file)
{
    EXPECT_TRUE(osgDB::writeNodeFile(node, file)) << "cannot write " << file;
    osg::ref_ptr<osg::Node> read = osgDB::readRefNodeFile(file);
    EXPECT_TRUE(read.valid()) << "cannot read " << file << " back (is OSG_LIBRARY_PATH the build's lib?)";
    return read;
}

void expectSameSkin(const Skin& a, const Skin& b)
{
    EXPECT_EQ(a.getName(), b.getName());
    EXPECT_EQ(a.getMethod(), b.getMethod());
    EXPECT_EQ(a.getNormalTransform(), b.getNormalTransform());
    EXPECT_EQ(a.getJointNames(), b.getJointNames());
    for (unsigned j = 0; j < a.getNumJoints(); ++j) EXPECT_EQ(a.getInverseBindMatrix(j), b.getInverseBindMatrix(j));
    ASSERT_EQ(a.getNumVertices(), b.getNumVertices());
    EXPECT_EQ(a.hasNormals(), b.hasNormals());
    EXPECT_EQ(a.hasTangents(), b.hasTangents());
    unsigned weightsChanged = 0;
    for (unsigned v = 0; v < a.getNumVertices(); ++v)
    {
        ASSERT_EQ(a.getBindPosition(v), b.getBindPosition(v)) << "vertex " << v;
        ASSERT_EQ(a.getNumInfluences(v), b.getNumInfluences(v)) << "vertex " << v;
        for (unsigned k = 0; k < a.getNumInfluences(v); ++k)
        {
            EXPECT_EQ(a.getInfluenceJoints(v)[k], b.getInfluenceJoints(v)[k]) << "vertex " << v;
            if (a.getInfluenceWeights(v)[k] != b.getInfluenceWeights(v)[k]) ++weightsChanged;
        }
    }
    EXPECT_EQ(weightsChanged, 0u);
    for (std::size_t i = 0; i < a.getVertices().normals.size(); ++i)
        EXPECT_EQ(a.getVertices().normals[i], b.getVertices().normals[i]);
}

} // namespace

TEST(SkinnedMeshSerialization, ABrokenSkinFailsTheReadWithItsMessage)
{
    const RiggedModelActor read = readCesiumMan();
    const std::string file = written("cesium_man_broken.osgt");
    ASSERT_TRUE(osgDB::writeNodeFile(*read.sceneNode, file));
    std::string text = contentsOf(file);
    // The first vertex's first influence names joint 99 of 19.
    const std::size_t vertices = text.find("Vertices ");
    ASSERT_NE(vertices, std::string::npos);
    const std::size_t firstLine = text.find('{', vertices) + 1;
    std::istringstream line(text.substr(firstLine, text.find('\n', firstLine + 1) - firstLine));
    float x, y, z, nx, ny, nz;
    unsigned count, joint;
    line >> x >> y >> z >> nx >> ny >> nz >> count >> joint;
    std::ostringstream numbers;
    const std::size_t jointAt = text.find(" " + std::to_string(count) + " " + std::to_string(joint) + " ", firstLine);
    ASSERT_NE(jointAt, std::string::npos);
    text.replace(jointAt, std::to_string(count).size() + std::to_string(joint).size() + 3,
                 " " + std::to_string(count) + " 99 ");
    std::ofstream(file, std::ios::binary) << text;
    osgDB::ReaderWriter::ReadResult result = osgDB::Registry::instance()->readNode(file, nullptr);
    EXPECT_FALSE(result.validNode());
    EXPECT_NE(result.message().find("skinned mesh: skin"), std::string::npos) << result.message();
    EXPECT_NE(result.message().find("joint index 99 is out of range"), std::string::npos) << result.message();
}

TEST(SkinnedMeshSerialization, ASkinnedActorReadsBackInlineEqualAndWritesTheSameBytes)
{
    for (const char* extension : {"osgt", "osgb"})
    {
        const RiggedModelActor read = readCesiumMan(SkinnedMesh::CPU_SKINNING);
        const SkinnedMesh& original = *read.skinnedMeshes[0];
        const std::string first = written(std::string("cesium_man.") + extension);
        osg::ref_ptr<osg::Node> back = writeAndReadBack(*read.sceneNode, first);
        ASSERT_TRUE(back.valid());
        ActorNode* actor = dynamic_cast<ActorNode*>(back.get());
        ASSERT_TRUE(actor);
        const std::vector<SkinnedMesh*> meshes = findSkinnedMeshes(*actor);
        ASSERT_EQ(meshes.size(), 1u);
        const SkinnedMesh& mesh = *meshes[0];
        EXPECT_TRUE(mesh.getSetupError().empty()) << mesh.getSetupError();
        expectSameSkin(*original.getSkin(), *mesh.getSkin());
        EXPECT_EQ(mesh.getSkinningPath(), SkinnedMesh::CPU_SKINNING);
        EXPECT_EQ(mesh.getPaletteStorage(), original.getPaletteStorage());
        ASSERT_TRUE(mesh.getSurface());
        EXPECT_EQ(mesh.getSurface()->getPrimitiveSet(0)->getNumIndices(),
                  original.getSurface()->getPrimitiveSet(0)->getNumIndices());
        ASSERT_TRUE(mesh.getStateSet());
        EXPECT_TRUE(mesh.getStateSet()->getTextureAttribute(0, osg::StateAttribute::TEXTURE));

        // The mesh read writes back the same bytes as the mesh written (its skin, surface, material and settings;
        // the actor's definition is ActorDefinitionObject's to write).
        const std::string meshFile = written(std::string("cesium_man_mesh.") + extension);
        const std::string meshAgain = written(std::string("cesium_man_mesh_again.") + extension);
        ASSERT_TRUE(osgDB::writeObjectFile(original, meshFile));
        ASSERT_TRUE(osgDB::writeObjectFile(mesh, meshAgain));
        EXPECT_TRUE(contentsOf(meshFile) == contentsOf(meshAgain)) << meshFile << " and " << meshAgain << " differ";

        // It walks and deforms as the original: the same vertices at the same time.
        FrameDriver originalDriver(read.sceneNode.get()), backDriver(actor);
        for (unsigned frame = 0; frame <= 10; ++frame)
        {
            originalDriver.frame(frame / 30.0);
            backDriver.frame(frame / 30.0);
        }
        osg::ref_ptr<osg::Vec3Array> a = new osg::Vec3Array, b = new osg::Vec3Array;
        ASSERT_TRUE(original.computeSkinnedVertices(*read.actor, *a));
        ASSERT_TRUE(mesh.computeSkinnedVertices(*actor, *b));
        EXPECT_EQ(maxDistance(*a, *b), 0.0) << extension;
    }
}

TEST(SkinnedMeshSerialization, AVertexWordThatIsNotANumberFailsTheReadNamingIt)
{
    const RiggedModelActor read = readCesiumMan();
    const std::string file = written("cesium_man_not_a_number.osgt");
    ASSERT_TRUE(osgDB::writeNodeFile(*read.sceneNode, file));
    std::string text = contentsOf(file);
    // The first vertex's x becomes a word no number reads as.
    const std::size_t vertices = text.find("Vertices ");
    ASSERT_NE(vertices, std::string::npos);
    std::size_t x = text.find('{', vertices) + 1;
    while (std::isspace(static_cast<unsigned char>(text[x]))) ++x;
    text.replace(x, text.find(' ', x) - x, "1.5x");
    std::ofstream(file, std::ios::binary) << text;
    osgDB::ReaderWriter::ReadResult result = osgDB::Registry::instance()->readNode(file, nullptr);
    EXPECT_FALSE(result.validNode());
    EXPECT_NE(result.message().find("skinned mesh: a vertex"), std::string::npos) << result.message();
    EXPECT_NE(result.message().find("1.5x"), std::string::npos) << result.message();
}
