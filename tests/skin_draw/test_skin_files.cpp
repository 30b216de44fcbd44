// Skins by reference in .actor files (the "skin" statement, docs/actor-format.md): a statement given wrongly, a file
// that cannot be found and a skin the actor's joints do not fit are refused with the .actor file's line; an actor
// made from a rigged model is written with a reference to the file, not its vertices, and reads back wearing the same
// skins, deformed the same at the same pose; a file named relatively is found next to the .actor file.
#include "SkinDrawTestUtil"

#include <osgActor/ActorSceneIO>
#include <osgActor/core/SamplingJob>
#include <osgActor/io/ActorReader>
#include <osgActor/io/ActorWriter>

#include <osgDB/FileNameUtils>

#include <gtest/gtest.h>

#include <sstream>

using namespace osgActor;
using namespace osgActor::test;

namespace {

ActorReadResult readText(const std::string& text, const std::string& fileName = "skins.actor")
{
    std::istringstream in(text);
    return readActor(in, fileName);
}

/** The actor a .actor text describes, made as the plugin makes it (fileName: where the file would be). */
ActorNodeResult createFromText(const std::string& text, const std::string& fileName)
{
    const ActorReadResult read = readText(text, fileName);
    EXPECT_TRUE(read) << read.error;
    if (!read) return ActorNodeResult{nullptr, read.error};
    return createActorNode(read.document, read.definition, fileName, nullptr);
}

std::string writtenText(const ActorNode& actor)
{
    std::ostringstream out;
    writeActor(out, extractActorDocument(actor));
    return out.str();
}

std::string inQuotes(const std::string& text) { return "\"" + text + "\""; }

/** Gives to actor the DOF values of model, by DOF name. */
void copyPoseByName(const ActorNode& model, ActorNode& actor)
{
    const ActorDefinition& from = *model.getDefinition();
    const ActorDefinition& to = *actor.getDefinition();
    ASSERT_EQ(from.getNumDofs(), to.getNumDofs());
    std::vector<double> dofs(to.getNumDofs());
    for (unsigned d = 0; d < from.getNumDofs(); ++d)
    {
        const int there = to.findDof(from.getDofName(d));
        ASSERT_GE(there, 0) << from.getDofName(d);
        dofs[static_cast<unsigned>(there)] = model.getDof(d);
    }
    ASSERT_TRUE(actor.setDofs(dofs));
}

} // namespace

TEST(SkinFiles, ASkinStatementWithABlockNoFileOrTwiceTheSameFileIsRefusedWithItsLine)
{
    const std::string head = "osgactor 1\nactor a {\n    joint root { dof rx }\n";
    ActorReadResult read = readText(head + "    skin \"a.gltf\" { scale 2 }\n}\n");
    EXPECT_FALSE(read);
    EXPECT_NE(read.error.find("skins.actor:4: 'skin' takes no block"), std::string::npos) << read.error;

    read = readText(head + "    skin\n}\n");
    EXPECT_FALSE(read);
    EXPECT_NE(read.error.find("skins.actor:4: 'skin' takes 1 value, not 0"), std::string::npos) << read.error;

    read = readText(head + "    skin \"a.gltf\"\n    skin \"a.gltf\"\n}\n");
    EXPECT_FALSE(read);
    EXPECT_NE(read.error.find("skins.actor:5: skin file 'a.gltf' is given twice"), std::string::npos) << read.error;
}

TEST(SkinFiles, ASkinFileThatCannotBeFoundFailsTheActorWithItsLine)
{
    const ActorNodeResult made = createFromText(
        "osgactor 1\nactor a {\n    joint root { dof rx }\n    skin \"nowhere/hero.gltf\"\n}\n",
        std::string(OSGACTOR_TEST_BINARY_DIR) + "/missing.actor");
    EXPECT_FALSE(made.actor.valid());
    EXPECT_NE(made.error.find("missing.actor:4: cannot find the skin file 'nowhere/hero.gltf'"), std::string::npos)
        << made.error;
}

TEST(SkinFiles, ASkinWhoseJointTheActorLacksFailsTheActorNamingTheJoint)
{
    // Cesium Man's skin on an actor of one joint named like none of its own.
    const ActorNodeResult made = createFromText(
        "osgactor 1\nactor a {\n    joint root { dof rx }\n    skin " + inQuotes(cesiumManFile()) + "\n}\n",
        std::string(OSGACTOR_TEST_BINARY_DIR) + "/unfit.actor");
    EXPECT_FALSE(made.actor.valid());
    EXPECT_NE(made.error.find("unfit.actor:4: " + cesiumManFile() + ": "), std::string::npos) << made.error;
    EXPECT_NE(made.error.find("joint 0 'Skeleton_torso_joint_1' is not a joint of actor 'a'"), std::string::npos)
        << made.error;
}

TEST(SkinFiles, AnActorOfARiggedModelIsWrittenWithItsSkinsByReferenceAndReadsBackWearingThem)
{
    const RiggedModelActor original = readCesiumMan();
    const std::string text = writtenText(*original.actor);
    ASSERT_NE(text.find("    skin " + inQuotes(cesiumManFile()) + "\n"), std::string::npos) << text.substr(0, 400);
    // By reference: that line is all the skins add to the text (no vertex, weight or inverse bind matrix).
    {
        osg::ref_ptr<osg::Node> skins = original.skinnedMeshes[0]->getParent(0);
        ASSERT_TRUE(original.actor->removeChild(skins.get()));
        const std::string withoutSkins = writtenText(*original.actor);
        original.actor->addChild(skins.get());
        std::string withoutSkinLine = text;
        const std::string skinLine = "    skin " + inQuotes(cesiumManFile()) + "\n";
        withoutSkinLine.erase(withoutSkinLine.find(skinLine), skinLine.size());
        EXPECT_TRUE(withoutSkinLine == withoutSkins);
    }

    const ActorNodeResult back = createFromText(text, std::string(OSGACTOR_TEST_BINARY_DIR) + "/cesium_man.actor");
    ASSERT_TRUE(back.actor.valid()) << back.error;
    // What it reads back writes the same text.
    EXPECT_TRUE(writtenText(*back.actor) == text);
    const std::vector<SkinnedMesh*> meshes = findSkinnedMeshes(*back.actor);
    ASSERT_EQ(meshes.size(), original.skinnedMeshes.size());
    const SkinnedMesh& mesh = *meshes[0];
    EXPECT_TRUE(mesh.getSetupError().empty()) << mesh.getSetupError();
    EXPECT_EQ(mesh.getSkin()->getJointNames(), original.skinnedMeshes[0]->getSkin()->getJointNames());
    ASSERT_TRUE(mesh.getStateSet());
    EXPECT_TRUE(mesh.getStateSet()->getTextureAttribute(0, osg::StateAttribute::TEXTURE));

    // Bound to the actor read back: at several poses of the clip, the same vertices as the original's.
    const ClipPtr clip = original.rigged.clips.front();
    const ActorDefinition& definition = *original.actor->getDefinition();
    osg::ref_ptr<osg::Vec3Array> previous;
    for (double t : {0.0, 0.5, 1.2})
    {
        std::vector<double> values(clip->getNumChannels());
        ClipCursor cursor;
        clip->initCursor(cursor);
        sampleEveryChannel(*clip, t, cursor, values);
        std::vector<double> dofs = definition.getDefaultDofs();
        for (unsigned c = 0; c < clip->getNumChannels(); ++c)
            dofs[definition.findDof(clip->getChannel(c).target)] = values[c];
        ASSERT_TRUE(original.actor->setDofs(dofs));
        copyPoseByName(*original.actor, *back.actor);
        osg::ref_ptr<osg::Vec3Array> expected = new osg::Vec3Array, actual = new osg::Vec3Array;
        ASSERT_TRUE(original.skinnedMeshes[0]->computeSkinnedVertices(*original.actor, *expected));
        ASSERT_TRUE(mesh.computeSkinnedVertices(*back.actor, *actual));
        osg::BoundingBox box;
        for (const osg::Vec3& vertex : *expected) box.expandBy(vertex);
        // The DOFs and the definition go through 12 significant digits.
        EXPECT_LT(maxDistance(*expected, *actual), 1e-6 * box.radius()) << "t = " << t;
        // The poses differ, so the comparison is of deformed meshes.
        if (previous)
        {
            EXPECT_GT(maxDistance(*expected, *previous), 1e-3 * box.radius()) << "t = " << t;
        }
        previous = expected;
    }
}

TEST(SkinFiles, ASkinFileNamedRelativelyIsFoundNextToTheActorFile)
{
    const RiggedModelActor original = readCesiumMan();
    std::string text = writtenText(*original.actor);
    const std::string absolute = inQuotes(cesiumManFile());
    const std::size_t at = text.find(absolute);
    ASSERT_NE(at, std::string::npos);
    text.replace(at, absolute.size(), inQuotes(osgDB::getSimpleFileName(cesiumManFile())));

    // A .actor file beside the glTF file (the name only places the lookup: nothing is written there).
    const std::string beside = osgDB::getFilePath(cesiumManFile()) + "/hero.actor";
    const ActorNodeResult back = createFromText(text, beside);
    ASSERT_TRUE(back.actor.valid()) << back.error;
    ASSERT_EQ(findSkinnedMeshes(*back.actor).size(), 1u);
    // Written back as named.
    EXPECT_NE(writtenText(*back.actor).find("    skin \"CesiumMan.gltf\"\n"), std::string::npos);

    // Elsewhere, the same text does not find it.
    const ActorNodeResult elsewhere = createFromText(text, std::string(OSGACTOR_TEST_BINARY_DIR) + "/hero.actor");
    EXPECT_FALSE(elsewhere.actor.valid());
    EXPECT_NE(elsewhere.error.find("cannot find the skin file 'CesiumMan.gltf'"), std::string::npos)
        << elsewhere.error;
}
