// Collada, FBX, DirectX and osgAnimation files as actors (readRiggedModelActor) and through the pseudo-loader
// ("hero.fbx.actor", as osgviewer reads it), good files and broken ones.
#include "ImportTestUtil"

#include <osgActor/ActorNode>
#include <osgActor/RiggedModelActor>

#include <osg/MatrixTransform>
#include <osgDB/Registry>

#include <gtest/gtest.h>

using namespace osgActor;
using namespace osgActor::test;

namespace {

osgDB::ReaderWriter::ReadResult readAsOsgviewerDoes(const std::string& file)
{
    return osgDB::Registry::instance()->readNode(file, osg::ref_ptr<osgDB::Options>(new osgDB::Options).get());
}

/** The actor of a pseudo-loaded node: the node itself, or the one below the transform holding a root scale. */
const ActorNode* actorOf(osg::Node* node)
{
    if (const auto* actor = dynamic_cast<const ActorNode*>(node)) return actor;
    const auto* above = dynamic_cast<const osg::MatrixTransform*>(node);
    return above && above->getNumChildren() == 1 ? dynamic_cast<const ActorNode*>(above->getChild(0)) : nullptr;
}

std::string legFile() { return std::string(OSGACTOR_TEST_SOURCE_DIR) + "/import/data/osganimation/leg.osgt"; }

} // namespace

TEST(RiggedFileFormats, ThePseudoLoaderRefusesBrokenFilesWithTheReadersMessage)
{
    const std::string brokenBones = assimpModels("X/anim_test.x");
    osgDB::ReaderWriter::ReadResult bones = readAsOsgviewerDoes(brokenBones + ".actor");
    EXPECT_FALSE(bones.validNode());
    EXPECT_NE(bones.message().find(brokenBones + ": meshes[0] 'pCylinder1'.bones[2] 'joint3': names no node"),
              std::string::npos) << bones.message();
    const std::string unreadable = assimpModels("Collada/library_animation_clips.dae");
    osgDB::ReaderWriter::ReadResult parse = readAsOsgviewerDoes(unreadable + ".actor");
    EXPECT_FALSE(parse.validNode());
    EXPECT_NE(parse.message().find(unreadable + ": Assimp cannot read it: Cannot parse string"), std::string::npos)
        << parse.message();
}

TEST(RiggedFileFormats, ThePseudoLoaderMakesActorsOfColladaFbxDirectXAndOsgAnimationFiles)
{
    struct Case
    {
        std::string file;
        unsigned joints;
        std::size_t clips;
    };
    // Joints: the skins' bones, the animated nodes and their ancestors (for leg.osgt, the transforms of its rig
    // down to the foot, which carries a rigid mesh).
    for (const Case& c : {Case{assimpModels("FBX/huesitos.fbx"), 11u, 1u}, Case{assimpModels("X/Testwuson.X"), 40u, 3u},
                          Case{assimpModels("Collada/box_nested_animation.dae"), 3u, 1u}, Case{legFile(), 6u, 2u}})
    {
        osgDB::ReaderWriter::ReadResult read = readAsOsgviewerDoes(c.file + ".actor");
        ASSERT_TRUE(read.validNode()) << c.file << ": " << read.message();
        const ActorNode* actor = actorOf(read.getNode());
        ASSERT_TRUE(actor) << c.file;
        EXPECT_EQ(actor->getDefinition()->getNumJoints(), c.joints) << c.file;
        ASSERT_TRUE(actor->getClipLibrary()) << c.file;
        EXPECT_EQ(actor->getClipLibrary()->getNumClips(), c.clips) << c.file;
    }
}

TEST(RiggedFileFormats, AnActorPlaysTheClipItIsAskedFor)
{
    std::string error;
    RiggedModelActorOptions options;
    options.clip = "Wuson_Walk";
    const RiggedModelActor walk = readRiggedModelActor(assimpModels("X/Testwuson.X"), options, error);
    ASSERT_TRUE(walk.actor) << error;
    EXPECT_EQ(walk.rigged.skins.size(), 1u);
    options.clip = "Wuson_Swim";
    EXPECT_FALSE(readRiggedModelActor(assimpModels("X/Testwuson.X"), options, error).actor);
    EXPECT_NE(error.find("no animation named 'Wuson_Swim'"), std::string::npos) << error;
}
