// Collada, FBX, DirectX and osgAnimation files as actors (readRiggedModelActor) and through the pseudo-loader
// ("hero.fbx.actor", as osgviewer reads it), good files and broken ones.
#include "ImportTestUtil"

#include <osgActor/ActorNode>
#include <osgActor/RiggedModelActor>
#include <osgActor/core/skin/SkinBinding>

#include <osg/Geode>
#include <osg/MatrixTransform>
#include <osgAnimation/RigGeometry>
#include <osgDB/ReadFile>
#include <osgDB/Registry>
#include <osgDB/WriteFile>

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

/** The RigGeometries of a scene graph, depth first. */
void forEachRigGeometry(const osg::Node& node, std::vector<const osgAnimation::RigGeometry*>& rigs)
{
    if (const osg::Geode* geode = node.asGeode())
        for (unsigned d = 0; d < geode->getNumDrawables(); ++d)
            if (const auto* rig = dynamic_cast<const osgAnimation::RigGeometry*>(geode->getDrawable(d)))
                rigs.push_back(rig);
    if (const osg::Group* group = node.asGroup())
        for (unsigned c = 0; c < group->getNumChildren(); ++c) forEachRigGeometry(*group->getChild(c), rigs);
}

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

TEST(RiggedFileFormats, AColladaSceneOfOsgsOwnPluginSavedAsOsgtBecomesAnActorWithItsSkinsAndClips)
{
    // What an OSG user has: osgdb_dae's osgAnimation scene of a Collada file (a skinned character with two clips;
    // Assimp cannot read this file), saved by osgDB as .osgt ("osgconv in.dae out.osgt").
    osg::ref_ptr<osg::Node> scene = osgDB::readRefNodeFile(assimpModels("Collada/library_animation_clips.dae"));
    ASSERT_TRUE(scene);
    const std::string path = written("library_animation_clips.osgt");
    ASSERT_TRUE(osgDB::writeNodeFile(*scene, path));
    std::string error;
    const RiggedModelActor read = readRiggedModelActor(path, RiggedModelActorOptions(), error);
    ASSERT_TRUE(read.actor) << error;
    ASSERT_TRUE(read.actor->getClipLibrary());
    EXPECT_EQ(read.actor->getClipLibrary()->getNumClips(), 2u);
    // A skin per RigGeometry of the scene, in its order, with a joint per bone its influence map weighs, each bound
    // to the actor's joint of that bone's name.
    std::vector<const osgAnimation::RigGeometry*> rigs;
    forEachRigGeometry(*scene, rigs);
    ASSERT_FALSE(rigs.empty());
    ASSERT_EQ(read.rigged.skins.size(), rigs.size());
    for (std::size_t s = 0; s < rigs.size(); ++s)
    {
        const Skin& skin = *read.rigged.skins[s].skin;
        const SkinBinding binding = bindSkinToDefinition(skin, *read.actor->getDefinition());
        EXPECT_TRUE(binding) << binding.error;
        ASSERT_EQ(skin.getNumJoints(), rigs[s]->getInfluenceMap()->size());
        for (unsigned j = 0; j < skin.getNumJoints(); ++j)
            EXPECT_EQ(rigs[s]->getInfluenceMap()->count(skin.getJointName(j)), 1u) << skin.getJointName(j);
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
