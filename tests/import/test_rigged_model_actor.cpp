// The OSG layer: an ActorNode made from a glTF file (readRiggedModelActor), and the pseudo-loader that gives it to
// osgDB ("hero.gltf.actor", as osgviewer reads it).
#include "GltfTestFile"
#include "ImportTestUtil"

#include <osgActor/RiggedModelActor>
#include <osgActor/core/ClipPlayer>

#include <osg/Geode>
#include <osg/Geometry>
#include <osg/MatrixTransform>
#include <osg/Texture2D>
#include <osgDB/Registry>

#include <gtest/gtest.h>

using namespace osgActor;
using namespace osgActor::test;

namespace {

/** Reads through osgDB's registry, with an option string, as osgviewer does. */
osgDB::ReaderWriter::ReadResult readAsOsgviewerDoes(const std::string& file, const char* optionString = "")
{
    return osgDB::Registry::instance()->readNode(file, osg::ref_ptr<osgDB::Options>(new osgDB::Options(optionString)).get());
}

/** The geometries drawn below a node. */
std::vector<const osg::Geometry*> geometriesBelow(const osg::Node& node)
{
    std::vector<const osg::Geometry*> found;
    if (const osg::Geode* geode = node.asGeode())
        for (unsigned i = 0; i < geode->getNumDrawables(); ++i)
            if (const osg::Geometry* geometry = geode->getDrawable(i)->asGeometry()) found.push_back(geometry);
    if (const osg::Group* group = node.asGroup())
        for (unsigned i = 0; i < group->getNumChildren(); ++i)
        {
            const std::vector<const osg::Geometry*> more = geometriesBelow(*group->getChild(i));
            found.insert(found.end(), more.begin(), more.end());
        }
    return found;
}

} // namespace

TEST(RiggedModelActor, RefusesABrokenFileAndAnUnknownClip)
{
    std::string error;
    const std::string broken = gltf2("IndexOutOfRange/IndexOutOfRange.gltf");
    EXPECT_FALSE(readRiggedModelActor(broken, RiggedModelActorOptions(), error).actor);
    EXPECT_EQ(error.compare(0, broken.size() + 25, broken + ": meshes[0].primitives[0]"), 0) << error;

    RiggedModelActorOptions options;
    options.clip = "dance";
    EXPECT_FALSE(readRiggedModelActor(cesiumMan(), options, error).actor);
    EXPECT_EQ(error, cesiumMan() + ": no animation named 'dance'");
}

TEST(RiggedModelActor, OptionStringsSetTheImport)
{
    RiggedModelActorOptions options;
    std::string error;
    EXPECT_FALSE(parseRiggedModelOptionString("mode=sideways", options, error));
    EXPECT_EQ(error, "option mode must be loop, once or pingpong, not 'sideways'");
    EXPECT_FALSE(parseRiggedModelOptionString("rootScale=big", options, error));
    ASSERT_TRUE(parseRiggedModelOptionString("clip=Walk mode=once rootScale=lengths noFigure yUp scale=2", options, error));
    EXPECT_FALSE(options.zUp);
    EXPECT_EQ(options.clip, "Walk");
    EXPECT_EQ(options.playMode, PlayMode::Once);
    EXPECT_EQ(options.rootScale, RootScale::InLengths);
    EXPECT_FALSE(options.addFigure);
}

TEST(RiggedModelActor, CesiumManPlaysItsFirstAnimation)
{
    std::string error;
    const RiggedModelActor read = readRiggedModelActor(cesiumMan(), RiggedModelActorOptions(), error);
    ASSERT_TRUE(read.actor) << error;
    EXPECT_EQ(read.sceneNode.get(), read.actor.get());
    EXPECT_EQ(read.actor->getName(), "CesiumMan");
    ASSERT_TRUE(read.actor->getClipLibrary());
    EXPECT_TRUE(read.actor->getClipLibrary()->getClip("animation0"));
    ASSERT_EQ(read.actor->getControllers().size(), 1u);
    const auto player = std::dynamic_pointer_cast<ClipPlayer>(read.actor->getControllers()[0]);
    ASSERT_TRUE(player);
    EXPECT_EQ(player->getClip()->getName(), "animation0");
    EXPECT_EQ(player->getPlayMode(), PlayMode::Loop);
    // It stands in OSG's frame: the neck (Skeleton_neck_joint_2) 1 to 1.5 above the feet, along +Z.
    const osg::Vec3d head = read.actor->getJointWorldPosition(unsigned(read.actor->getDefinition()->findJoint("Skeleton_neck_joint_2")));
    EXPECT_GT(head.z(), 1.0);
    EXPECT_LT(head.z(), 1.5);
    EXPECT_LT(std::abs(head.y()), 0.3);
    // The skin is kept for the skinned drawables, bound to the actor's joints.
    ASSERT_EQ(read.rigged.skins.size(), 1u);
    EXPECT_EQ(read.rigged.definition, read.actor->getDefinition());
}

TEST(RiggedModelActor, ARigidTexturedMeshIsDrawnOnItsJoint)
{
    std::string error;
    RiggedModelActorOptions options;
    options.addFigure = false;
    const RiggedModelActor read = readRiggedModelActor(gltf2("BoxTextured-glTF/BoxTextured.gltf"), options, error);
    ASSERT_TRUE(read.actor) << error;
    const std::vector<const osg::Geometry*> drawn = geometriesBelow(*read.actor->getSkeletonNode(1u));
    ASSERT_EQ(drawn.size(), 1u);
    const osg::Geometry& box = *drawn[0];
    EXPECT_EQ(box.getVertexArray()->getNumElements(), 24u);
    ASSERT_TRUE(box.getTexCoordArray(0));
    ASSERT_TRUE(box.getStateSet());
    const osg::Texture2D* texture =
        dynamic_cast<const osg::Texture2D*>(box.getStateSet()->getTextureAttribute(0, osg::StateAttribute::TEXTURE));
    ASSERT_TRUE(texture);
    EXPECT_EQ(texture->getImage()->s(), 211);
    EXPECT_EQ(texture->getWrap(osg::Texture::WRAP_S), osg::Texture::MIRROR);
    EXPECT_TRUE(geometriesBelow(*read.actor->getSkeletonNode(0u)).size() == 1u); // the same box, below the child
}

TEST(RiggedModelPseudoLoader, ReadsAGltfFileAsAnActor)
{
    osgDB::ReaderWriter::ReadResult read = readAsOsgviewerDoes(cesiumMan() + ".actor");
    ASSERT_TRUE(read.validNode()) << read.message();
    const ActorNode* actor = dynamic_cast<ActorNode*>(read.getNode());
    ASSERT_TRUE(actor);
    EXPECT_EQ(actor->getDefinition()->getNumJoints(), 21u);
}

TEST(RiggedModelPseudoLoader, PutsARootScaleAboveTheActor)
{
    GltfTestFile file;
    const int triangle = file.addFloats({0, 0, 0, 100, 0, 0, 0, 100, 0}, "VEC3");
    file.write(written("armature_box.gltf"),
               R"("scenes":[{"nodes":[0]}],"nodes":[{"name":"armature","scale":[0.01,0.01,0.01],"children":[1]},)"
               R"({"name":"hips","mesh":0}],"meshes":[{"primitives":[{"attributes":{"POSITION":)" +
                   std::to_string(triangle) + "}}]}]");
    osgDB::ReaderWriter::ReadResult read = readAsOsgviewerDoes(written("armature_box.gltf.actor"));
    ASSERT_TRUE(read.validNode()) << read.message();
    const osg::MatrixTransform* above = dynamic_cast<osg::MatrixTransform*>(read.getNode());
    ASSERT_TRUE(above);
    EXPECT_NEAR(above->getMatrix()(0, 0), 0.01, 1e-12);
    ASSERT_EQ(above->getNumChildren(), 1u);
    EXPECT_TRUE(dynamic_cast<const ActorNode*>(above->getChild(0)));
}

TEST(RiggedModelPseudoLoader, PassesOnTheReadersErrorAndOptions)
{
    const std::string broken = gltf2("RecursiveNodes/RecursiveNodes.gltf");
    osgDB::ReaderWriter::ReadResult read = readAsOsgviewerDoes(broken + ".actor");
    EXPECT_FALSE(read.validNode());
    EXPECT_NE(read.message().find(broken + ": nodes["), std::string::npos) << read.message();

    osgDB::ReaderWriter::ReadResult badOption = readAsOsgviewerDoes(cesiumMan() + ".actor", "mode=never");
    EXPECT_FALSE(badOption.validNode());
    EXPECT_NE(badOption.message().find("option mode must be"), std::string::npos) << badOption.message();
}
