/* Crowds through OSG's own formats: an ActorGroup keeps its thread count and its actors, and actors that share a
 * definition and a clip library (clones, or actors made from one definition) store them once, by osgDB's object
 * IDs, and read back sharing them again. Files written before the definition was shared still read. */
#include "PluginTestUtil"

#include "../nodes/NodeTestUtil"

#include <osgActor/ActorGroup>
#include <osgActor/ActorPartsText>
#include <osgActor/ActorSceneIO>
#include <osgActor/InstancedActorGroup>
#include <osgActor/core/ClipPlayer>
#include <osgActor/io/ActorWriter>

#include <osgDB/WriteFile>

#include <cstdlib>
#include <sys/stat.h>

using namespace osgActor;
using namespace osgActor::test;

// Debian's osgconv is not built with AddressSanitizer, so it cannot load the plugins of a build that is (ASan's
// runtime lives in the instrumented program): there, the osgconv test has nothing to run.
#if defined(__SANITIZE_ADDRESS__)
#define OSGACTOR_TEST_PLUGINS_INSTRUMENTED 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define OSGACTOR_TEST_PLUGINS_INSTRUMENTED 1
#endif
#endif

namespace {

/** The humanoid as .actor text: definition, geometry, pose, flags, clips, players and IK chains, to 12 digits. */
std::string actorText(const ActorNode& actor)
{
    std::ostringstream text;
    writeActor(text, extractActorDocument(actor));
    return text.str();
}

/** A crowd of clones of the humanoid under an ActorGroup of three threads: each clone placed, posed, (every
  * other one) waving at its own point of the clip, and culled or updated in its own way, so that no two are alike. */
osg::ref_ptr<ActorGroup> makeCrowd(unsigned numActors)
{
    osg::ref_ptr<ActorNode> prototype = readActorFile(dataFile("humanoid.actor"));
    if (!prototype || !prototype->getClipLibrary()) return nullptr;
    osg::ref_ptr<ActorGroup> crowd = new ActorGroup;
    crowd->setName("crowd");
    crowd->setNumThreads(3);
    for (unsigned i = 0; i < numActors; ++i)
    {
        osg::ref_ptr<ActorNode> actor = osg::clone(prototype.get(), osg::CopyOp::SHALLOW_COPY);
        actor->setName("walker " + std::to_string(i));
        actor->setPreTranslation(osg::Vec3d(1.5 * i, 0.25 * (i % 4), 0.0));
        actor->setDof("l_elbow.rx", -0.1 * (i % 10));
        // How the views treat it, in the three kinds: the defaults, culled node by node, an update policy.
        if (i % 3 == 1) actor->setCullMode(ActorNode::CULL_NODE_BY_NODE);
        if (i % 3 == 2)
        {
            ActorNode::UpdatePolicy policy;
            policy.onlyWhenSeen = true;
            policy.maxDistance = 40.0 + 0.1 * i;
            policy.halfRateBelowPixels = 0.1f * static_cast<float>(i);
            policy.quarterRateBelowPixels = 3.0f;
            actor->setUpdatePolicy(policy);
        }
        if (i % 2 == 0)
        {
            auto wave = std::make_shared<ClipPlayer>(actor->getClipLibrary()->getClip("wave"));
            wave->setName("waving");
            wave->seek(0.05 * i);
            actor->addController(wave);
        }
        crowd->addChild(actor.get());
    }
    return crowd;
}

std::string replaced(std::string text, const std::string& from, const std::string& to)
{
    const std::string::size_type at = text.find(from);
    EXPECT_NE(at, std::string::npos) << "the test must find what it replaces: " << from;
    if (at != std::string::npos) text.replace(at, from.size(), to);
    return text;
}

ActorNode* actorAt(osg::Group& group, unsigned i) { return dynamic_cast<ActorNode*>(group.getChild(i)); }

long fileSize(const std::string& path)
{
    struct stat status;
    return stat(path.c_str(), &status) == 0 ? static_cast<long>(status.st_size) : -1;
}

/** The crowd read back has the same thread count and actors, sharing one definition and one clip library. */
void expectSameCrowd(ActorGroup& original, osg::Node* read, const std::string& what)
{
    ActorGroup* back = dynamic_cast<ActorGroup*>(read);
    ASSERT_NE(back, nullptr) << what << ": not an osgActor::ActorGroup";
    EXPECT_EQ(back->getName(), original.getName()) << what;
    EXPECT_EQ(back->getNumThreads(), original.getNumThreads()) << what;
    EXPECT_NE(dynamic_cast<ActorGroupUpdateCallback*>(back->getUpdateCallback()), nullptr) << what;
    ASSERT_EQ(back->getNumChildren(), original.getNumChildren()) << what;
    for (unsigned i = 0; i < original.getNumChildren(); ++i)
    {
        const ActorNode* actor = actorAt(original, i);
        const ActorNode* actorBack = actorAt(*back, i);
        ASSERT_NE(actorBack, nullptr) << what << " child " << i;
        EXPECT_EQ(actorBack->getDofs(), actor->getDofs()) << what << " " << actor->getName();
        EXPECT_EQ(actorBack->getPreTranslation(), actor->getPreTranslation()) << what << " " << actor->getName();
        EXPECT_EQ(actorText(*actorBack), actorText(*actor)) << what << " " << actor->getName();
        EXPECT_EQ(actorBack->getDefinition(), actorAt(*back, 0)->getDefinition()) << what << ": one definition";
        EXPECT_EQ(actorBack->getClipLibrary(), actorAt(*back, 0)->getClipLibrary()) << what << ": one library";
        EXPECT_EQ(actorBack->getDefinitionObject(), actorAt(*back, 0)->getDefinitionObject()) << what;
    }
}

class CrowdFormats : public ::testing::TestWithParam<const char*>
{
};

} // namespace

// --- broken files first ---

TEST(CrowdFiles, AnActorWhoseDefinitionObjectIsMissingFailsTheRead)
{
    osg::ref_ptr<ActorGroup> arms = new ActorGroup;
    const ActorDefinitionPtr arm = makePlanarArm();
    for (const char* name : {"first arm", "second arm"})
    {
        osg::ref_ptr<ActorNode> actor = new ActorNode(arm);
        actor->setName(name);
        arms->addChild(actor.get());
    }
    const std::string good = outFile("no_definition_good.osgt");
    ASSERT_TRUE(osgDB::writeNodeFile(*arms, good));
    // The first actor's definition object, written in full, becomes an object of a class osgDB does not know,
    // which it skips: the actor is left without a definition.
    const std::string path =
        writeTextFile("no_definition.osgt", replaced(readTextFile(good), "osgActor::ActorDefinitionObject {",
                                                     "osgActor::NoSuchObject {"));
    osgDB::ReaderWriter::ReadResult result = osgDB::Registry::instance()->readNode(path, nullptr);
    EXPECT_FALSE(result.validNode());
    EXPECT_NE(result.message().find("actor 'first arm' has no definition"), std::string::npos) << result.message();
}

TEST(CrowdFiles, ADefinitionObjectHoldingMoreThanJointsOrACullModeIsRefused)
{
    std::vector<std::string> lines{"osgactor 1", "actor a {", " joint b { dof rz }",
                                   " clip c { channel b.rz { key 0 0 } }", "}"};
    std::string error;
    const std::string refusal = "the definition: a definition holds joints only, and this one has clips, "
                                "trajectories, players, IK chains, a cull mode, an update policy or other sections";
    EXPECT_EQ(readDefinitionLines(lines, "the definition", error), nullptr);
    EXPECT_EQ(error, refusal);
    // How the views treat an actor belongs to the actor, not to the definition its clones share.
    lines[3] = " cull node_by_node";
    EXPECT_EQ(readDefinitionLines(lines, "the definition", error), nullptr);
    EXPECT_EQ(error, refusal);
}

TEST(CrowdFiles, AClipLibraryHoldingPlayersOrAnUpdatePolicyIsRefused)
{
    std::string error;
    const ActorDefinitionPtr arm = makePlanarArm();
    EXPECT_EQ(readClipLines({"clip c { channel base.rz { key 0 0 } }", "player p { clip c }"}, arm, "the clips",
                            error),
              nullptr);
    const std::string refusal = "the clips: a clip library holds clips only, and this one has trajectories, players, "
                                "IK chains, a cull mode or an update policy";
    EXPECT_EQ(error, refusal);
    EXPECT_EQ(readClipLines({"update_policy { only_when_seen }"}, arm, "the clips", error), nullptr);
    EXPECT_EQ(error, refusal);
    EXPECT_EQ(readClipLines({"clip c { channel knee.rz { key 0 0 } }"}, arm, "the clips", error), nullptr);
    EXPECT_EQ(error, "the clips:1: channel 'knee.rz' names no DOF of the actor");
}

// --- the shared objects ---

TEST(CrowdFiles, ActorsOfOneDefinitionHoldOneDefinitionObjectAsLongAsOneLives)
{
    const ActorDefinitionPtr arm = makePlanarArm();
    osg::ref_ptr<ActorNode> first = new ActorNode(arm);
    osg::ref_ptr<ActorNode> second = new ActorNode(arm);
    osg::ref_ptr<ActorNode> clone = osg::clone(first.get(), osg::CopyOp::SHALLOW_COPY);
    ASSERT_NE(first->getDefinitionObject(), nullptr);
    EXPECT_EQ(first->getDefinitionObject()->getDefinition(), arm);
    EXPECT_EQ(second->getDefinitionObject(), first->getDefinitionObject()) << "made from one definition";
    EXPECT_EQ(clone->getDefinitionObject(), first->getDefinitionObject()) << "a clone";
    EXPECT_NE(osg::ref_ptr<ActorNode>(new ActorNode(makePlanarArm()))->getDefinitionObject(),
              first->getDefinitionObject())
        << "an equal definition is another definition";

    auto library = std::make_shared<ClipLibrary>();
    first->setClipLibrary(library);
    second->setClipLibrary(library);
    ASSERT_NE(first->getClipLibraryObject(), nullptr);
    EXPECT_EQ(second->getClipLibraryObject(), first->getClipLibraryObject());
    EXPECT_EQ(first->getClipLibraryObject()->getDefinitionObject(), first->getDefinitionObject());
    EXPECT_EQ(clone->getClipLibraryObject(), nullptr) << "the clone was made before the library was set";

    // Nothing but the actors keeps the wrapper: with the last of them it goes.
    osg::observer_ptr<const ActorDefinitionObject> wrapper = first->getDefinitionObject();
    first = nullptr;
    second = nullptr;
    EXPECT_TRUE(wrapper.valid()) << "the clone still holds it";
    clone = nullptr;
    EXPECT_FALSE(wrapper.valid());
}

TEST(CrowdFiles, AThousandClonesStoreTheirDefinitionAndClipsOnceAndReadBackSharingThem)
{
    // Actors without geometry, so that one actor's file is its definition, its clips and its own data only.
    osg::ref_ptr<ActorNode> humanoid = readActorFile(dataFile("humanoid.actor"));
    ASSERT_TRUE(humanoid.valid() && humanoid->getClipLibrary());
    osg::ref_ptr<ActorNode> prototype = new ActorNode(humanoid->getDefinition());
    prototype->setClipLibrary(humanoid->getClipLibrary());
    ASSERT_TRUE(osgDB::writeNodeFile(*prototype, outFile("one_actor.osgb")));
    // The clip library's file holds the definition too (the library names the definition its clips drive).
    ASSERT_TRUE(osgDB::writeObjectFile(*prototype->getClipLibraryObject(), outFile("shared_parts.osgb")));
    const long oneActor = fileSize(outFile("one_actor.osgb"));
    const long sharedParts = fileSize(outFile("shared_parts.osgb"));
    const long perActor = oneActor - sharedParts; // skeleton nodes, DOF vector, transforms, references
    ASSERT_GT(perActor, 0);

    constexpr unsigned kClones = 1000;
    osg::ref_ptr<osg::Group> crowd = new osg::Group;
    for (unsigned i = 0; i < kClones; ++i)
    {
        osg::ref_ptr<ActorNode> clone = osg::clone(prototype.get(), osg::CopyOp::SHALLOW_COPY);
        clone->setPreTranslation(osg::Vec3d(i, 0.0, 0.0));
        crowd->addChild(clone.get());
    }
    const std::string path = outFile("thousand_clones.osgb");
    ASSERT_TRUE(osgDB::writeNodeFile(*crowd, path));
    const long crowdSize = fileSize(path);
    // Each clone adds its own data, as one actor has it, and refers to the shared objects by ID instead of holding
    // them: a class name and an ID each, under a hundred bytes against the thousands of its own data. The 10%
    // margin covers that; a crowd that wrote the definition and clips with every clone exceeds it as soon as they
    // are a tenth of one actor's own data (here they are about half of it).
    EXPECT_LT(crowdSize, static_cast<long>(1.1 * kClones * perActor) + sharedParts)
        << "one actor " << oneActor << " bytes, definition and clips " << sharedParts << ", a thousand clones "
        << crowdSize;
    EXPECT_GT(2 * sharedParts, perActor) << "the bound above must tell the two ways of writing apart";
    std::cout << "[ measured ] one actor " << oneActor << " bytes, its definition and clips " << sharedParts
              << ", a thousand clones " << crowdSize << std::endl;

    osg::ref_ptr<osg::Node> node = osgDB::readRefNodeFile(path);
    osg::Group* back = node ? node->asGroup() : nullptr;
    ASSERT_NE(back, nullptr);
    ASSERT_EQ(back->getNumChildren(), kClones);
    const ActorNode* first = actorAt(*back, 0);
    ASSERT_TRUE(first && first->getDefinition() && first->getClipLibrary());
    EXPECT_NE(first->getDefinition(), prototype->getDefinition()) << "read, not found in memory";
    unsigned sharing = 0;
    for (unsigned i = 0; i < kClones; ++i)
    {
        const ActorNode* clone = actorAt(*back, i);
        sharing += clone && clone->getDefinition() == first->getDefinition() &&
                   clone->getClipLibrary() == first->getClipLibrary() &&
                   clone->getDefinitionObject() == first->getDefinitionObject() &&
                   clone->getPreTranslation() == osg::Vec3d(i, 0.0, 0.0);
    }
    EXPECT_EQ(sharing, kClones) << "clones in place, sharing the first one's definition and clip library";
}

// --- every format ---

TEST_P(CrowdFormats, ACrowdComesBackWithItsThreadCountAndItsActorsSharingOneDefinition)
{
    const std::string extension = GetParam();
    osg::ref_ptr<ActorGroup> crowd = makeCrowd(6);
    ASSERT_TRUE(crowd.valid());
    const std::string path = outFile("crowd." + extension);
    // OSG's own numbers (a shape's centre) keep every digit only with "precision 17" in the text formats.
    osg::ref_ptr<osgDB::Options> precise = new osgDB::Options("precision 17");
    ASSERT_TRUE(osgDB::writeNodeFile(*crowd, path, precise.get())) << path;
    osg::ref_ptr<osg::Node> back = osgDB::readRefNodeFile(path, precise.get());
    ASSERT_TRUE(back.valid()) << path;
    expectSameCrowd(*crowd, back.get(), extension);
    osg::Group* backGroup = back->asGroup();
    ASSERT_NE(backGroup, nullptr);
    EXPECT_EQ(actorAt(*backGroup, 1)->getCullMode(), ActorNode::CULL_NODE_BY_NODE);
    EXPECT_EQ(actorAt(*backGroup, 0)->getCullMode(), ActorNode::CULL_AS_ONE);
    const ActorNode::UpdatePolicy& policy = actorAt(*backGroup, 5)->getUpdatePolicy();
    EXPECT_TRUE(policy.onlyWhenSeen);
    EXPECT_EQ(policy.maxDistance, 40.5);
    EXPECT_EQ(policy.halfRateBelowPixels, 0.5f);
    EXPECT_EQ(policy.quarterRateBelowPixels, 3.0f);
    EXPECT_FALSE(actorAt(*backGroup, 4)->getUpdatePolicy().onlyWhenSeen);

    // It animates as the original does: the group's update runs the waving players of both alike.
    for (unsigned frame : {1u, 12u, 30u})
    {
        runUpdate(*crowd, frame);
        runUpdate(*back, frame);
    }
    osg::Group* group = back->asGroup();
    ASSERT_NE(group, nullptr);
    for (unsigned i = 0; i < crowd->getNumChildren(); ++i)
        EXPECT_EQ(actorAt(*group, i)->getDofs(), actorAt(*crowd, i)->getDofs()) << extension << " actor " << i;
    double elbow = 0.0;
    ASSERT_TRUE(actorAt(*group, 0)->getDof("r_elbow.rx", elbow));
    EXPECT_GT(std::abs(elbow), 1e-3) << "the wave moved the arm, so the comparison means something";
}

TEST_P(CrowdFormats, TheGroupsUpdateCallbackHasItsOwnWrapper)
{
    const std::string path = outFile(std::string("group_callback.") + GetParam());
    osg::ref_ptr<ActorGroupUpdateCallback> callback = new ActorGroupUpdateCallback;
    ASSERT_TRUE(osgDB::writeObjectFile(*callback, path));
    osg::ref_ptr<osg::Object> back = osgDB::readRefObjectFile(path);
    EXPECT_NE(dynamic_cast<ActorGroupUpdateCallback*>(back.get()), nullptr) << path;
}

TEST_P(CrowdFormats, AnEmptyGroupKeepsItsThreadCount)
{
    // A count that is not the default, alone, so that what comes back cannot be the constructor's.
    const std::string path = outFile(std::string("empty_group.") + GetParam());
    osg::ref_ptr<ActorGroup> group = new ActorGroup;
    group->setNumThreads(7);
    ASSERT_TRUE(osgDB::writeNodeFile(*group, path));
    osg::ref_ptr<ActorGroup> back = dynamic_cast<ActorGroup*>(osgDB::readRefNodeFile(path).get());
    ASSERT_TRUE(back.valid()) << path;
    EXPECT_EQ(back->getNumThreads(), 7u);
}

TEST_P(CrowdFormats, AnInstancedGroupKeepsItsDrawModeLightsThreadsAndActors)
{
    // Values that are not the defaults, so that what comes back cannot be the constructor's.
    osg::ref_ptr<ActorGroup> crowd = makeCrowd(2);
    ASSERT_TRUE(crowd.valid());
    osg::ref_ptr<InstancedActorGroup> group = new InstancedActorGroup;
    group->setNumThreads(5);
    group->setDrawMode(InstancedActorGroup::ORDINARY);
    group->setLights(6);
    for (unsigned i = 0; i < crowd->getNumChildren(); ++i) group->addChild(crowd->getChild(i));
    const std::string path = outFile(std::string("instanced_group.") + GetParam());
    ASSERT_TRUE(osgDB::writeNodeFile(*group, path));
    osg::ref_ptr<InstancedActorGroup> back = dynamic_cast<InstancedActorGroup*>(osgDB::readRefNodeFile(path).get());
    ASSERT_TRUE(back.valid()) << path;
    EXPECT_EQ(back->getNumThreads(), 5u);
    EXPECT_EQ(back->getDrawMode(), InstancedActorGroup::ORDINARY);
    EXPECT_EQ(back->getLights(), 6u);
    ASSERT_EQ(back->getNumChildren(), 2u);
    EXPECT_NE(actorAt(*back, 1), nullptr);
}

TEST_P(CrowdFormats, FilesWrittenBeforeTheDefinitionWasSharedStillRead)
{
    // old_form.* were written from old_form.actor by the serializers and wrappers that wrote one whole .actor text
    // per actor (tests/plugins/data/README.md).
    const std::string directory = std::string(OSGACTOR_TEST_SOURCE_DIR) + "/plugins/data/";
    osg::ref_ptr<ActorNode> expected = readActorFile(directory + "old_form.actor");
    osg::ref_ptr<ActorNode> old = readActorFile(directory + "old_form." + GetParam());
    ASSERT_TRUE(expected.valid() && old.valid());
    ASSERT_EQ(old->getControllers().size(), 2u) << "a clip's player and a trajectory's";
    ASSERT_EQ(old->getIkChains().size(), 1u);
    EXPECT_EQ(actorText(*old), actorText(*expected));
}

INSTANTIATE_TEST_SUITE_P(EveryFormat, CrowdFormats, ::testing::Values("osgt", "osgb", "osgx", "osg"),
                         [](const ::testing::TestParamInfo<const char*>& info) { return std::string(info.param); });

// --- Debian's osgconv ---

TEST(CrowdFiles, OsgconvTakesACrowdThroughEveryFormatAndBack)
{
    const std::string osgconv = OSGACTOR_TEST_OSGCONV;
    if (osgconv.empty()) GTEST_SKIP() << "osgconv is not installed (scripts/setup-debian.sh installs it)";
#ifdef OSGACTOR_TEST_PLUGINS_INSTRUMENTED
    GTEST_SKIP() << "Debian's osgconv cannot load the plugins of an AddressSanitizer build";
#endif
    osg::ref_ptr<ActorGroup> crowd = makeCrowd(4);
    ASSERT_TRUE(crowd.valid());
    // OSG's own numbers (a shape's centre) keep every digit only with "precision 17" in the text formats.
    osg::ref_ptr<osgDB::Options> precise = new osgDB::Options("precision 17");
    ASSERT_TRUE(osgDB::writeNodeFile(*crowd, outFile("osgconv_crowd.osgt"), precise.get()));
    // The environment has OSG_LIBRARY_PATH set to the build tree's plugins, which osgconv finds there.
    const std::string chain[] = {"osgconv_crowd.osgt", "osgconv_crowd.osgb", "osgconv_crowd.osgx",
                                 "osgconv_crowd.osg", "osgconv_crowd_back.osgt"};
    for (std::size_t i = 0; i + 1 < std::size(chain); ++i)
    {
        const std::string command = "'" + osgconv + "' -O 'precision 17' '" + outFile(chain[i]) + "' '" +
                                    outFile(chain[i + 1]) +
                                    "' > /dev/null";
        ASSERT_EQ(std::system(command.c_str()), 0) << command;
    }
    osg::ref_ptr<osg::Node> back = osgDB::readRefNodeFile(outFile(chain[std::size(chain) - 1]));
    ASSERT_TRUE(back.valid());
    expectSameCrowd(*crowd, back.get(), "osgconv");
}
