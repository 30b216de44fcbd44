/* Scenes with actors through OSG's own formats (.osgt, .osgb, .osgx with the serializer plugin, .osg with the
 * deprecated wrappers), written by osgDB::writeNodeFile and read back through osgDB's plugin lookup. */
#include "PluginTestUtil"

#include "../nodes/NodeTestUtil"

#include <osgActor/ActorUpdateCallback>
#include <osgActor/GlmOsg>
#include <osgActor/core/Trajectory>

#include <osgDB/WriteFile>

#include <cstring>

using namespace osgActor;
using namespace osgActor::test;

namespace {

/** The humanoid, posed, placed, with a hidden arm, inside a group as a user's scene would hold it. */
osg::ref_ptr<osg::Group> makeScene(bool blocked)
{
    osg::ref_ptr<ActorNode> actor = readActorFile(dataFile("humanoid.actor"));
    if (!actor) return nullptr;
    actor->setDof("l_elbow.rx", -1.1);
    actor->setDof("HumanoidRoot.tz", 0.123456789012345);
    actor->setDof("skullbase.rz", 0.3);
    actor->setPreTranslation(osg::Vec3d(2.5, -1.25, 0.0));
    actor->setPreRotation(osg::Quat(0.7, osg::Vec3d(0, 0, 1)));
    actor->setPostTranslation(osg::Vec3d(0, 0, 0.01));
    actor->setPostRotation(osg::Quat(0.1, osg::Vec3d(1, 0, 0)));
    actor->getSkeletonNode("r_elbow")->setHidden(true);
    // The blocked scene also has the bound mode that is not the default (a default is not written at all).
    if (blocked) actor->setBoundMode(ActorNode::BOUND_FOLLOWS_POSE);
    runUpdate(*actor, 1);
    // The frame computed local matrices only; bring the model matrices up to date too, so that the blocked
    // original answers queries with the pose it shows (main's lazy model matrices; see the report).
    actor->updatePose();
    actor->setBlocked(blocked);
    osg::ref_ptr<osg::Group> root = new osg::Group;
    root->addChild(actor.get());
    return root;
}

ActorNode* actorOf(osg::Node* root)
{
    osg::Group* group = root ? root->asGroup() : nullptr;
    return group && group->getNumChildren() == 1 ? dynamic_cast<ActorNode*>(group->getChild(0)) : nullptr;
}

std::string asActorText(const ActorNode& actor, const std::string& name)
{
    const std::string path = outFile(name);
    EXPECT_TRUE(osgDB::writeNodeFile(actor, path));
    return readTextFile(path);
}

void expectSameActor(const ActorNode& original, const ActorNode& back, const std::string& format)
{
    ASSERT_NE(back.getDefinition(), nullptr) << format;
    ASSERT_EQ(back.getNumDofs(), original.getNumDofs()) << format;
    for (unsigned d = 0; d < original.getNumDofs(); ++d)
        EXPECT_EQ(back.getDof(d), original.getDof(d)) << format << " " << original.getDefinition()->getDofName(d);
    EXPECT_EQ(back.getPreTranslation(), original.getPreTranslation()) << format;
    EXPECT_EQ(back.getPreRotation(), original.getPreRotation()) << format;
    EXPECT_EQ(back.getPostTranslation(), original.getPostTranslation()) << format;
    EXPECT_EQ(back.getPostRotation(), original.getPostRotation()) << format;
    EXPECT_EQ(back.getBlocked(), original.getBlocked()) << format;
    EXPECT_EQ(back.getBoundMode(), original.getBoundMode()) << format;
    ASSERT_EQ(back.getNumSkeletonNodes(), original.getNumSkeletonNodes()) << format;
    for (unsigned j = 0; j < original.getNumSkeletonNodes(); ++j)
    {
        EXPECT_EQ(back.getSkeletonNode(j)->getHidden(), original.getSkeletonNode(j)->getHidden()) << format;
        EXPECT_EQ(back.getSkeletonNode(j)->getBoundCoversRotations(),
                  original.getSkeletonNode(j)->getBoundCoversRotations())
            << format;
        EXPECT_EQ(back.getSkeletonNode(j)->getName(), original.getSkeletonNode(j)->getName()) << format;
        EXPECT_TRUE(vec3Near(back.getJointWorldPosition(j), original.getJointWorldPosition(j), 1e-11))
            << format << " joint " << original.getDefinition()->getJointName(j);
    }
}

/** The text formats write OSG's own numbers (shape centres and rotations) with 6 digits unless told otherwise. */
osg::ref_ptr<osgDB::Options> fullPrecision() { return new osgDB::Options("precision 17"); }

class OsgFormats : public ::testing::TestWithParam<const char*>
{
};

} // namespace

TEST_P(OsgFormats, AScenesActorsComeBackTheSameAndStillAnimate)
{
    const std::string extension = GetParam();
    osg::ref_ptr<osg::Group> scene = makeScene(false);
    ASSERT_TRUE(scene.valid());
    const std::string path = outFile("scene." + extension);
    ASSERT_TRUE(osgDB::writeNodeFile(*scene, path)) << path;

    osg::ref_ptr<osg::Node> back = osgDB::readRefNodeFile(path);
    ASSERT_TRUE(back.valid()) << "osgDB found no plugin for " << path;
    ActorNode* actor = actorOf(back.get());
    ASSERT_NE(actor, nullptr) << extension << ": the actor did not come back as an osgActor::ActorNode";
    expectSameActor(*actorOf(scene.get()), *actor, extension);

    // It animates: its update callback came back, and a frame writes the new pose into the skeleton nodes.
    ASSERT_NE(dynamic_cast<ActorUpdateCallback*>(actor->getUpdateCallback()), nullptr) << extension;
    runUpdate(*back, 1);
    const unsigned elbow = static_cast<unsigned>(actor->getJointIndex("l_elbow"));
    ASSERT_TRUE(actor->setDof("l_elbow.rx", -0.5));
    runUpdate(*back, 2);
    EXPECT_EQ(actor->getSkeletonNode(elbow)->getMatrix(), toOsg(actor->getPose().getLocalMatrix(elbow)));
    const osg::Matrixd expected = osg::Matrixd::rotate(-0.5, osg::X_AXIS) * osg::Matrixd::translate(0, 0, -0.3);
    EXPECT_TRUE(actor->getSkeletonNode(elbow)->getMatrix().compare(expected) == 0 ||
                vec3Near(osg::Vec3d(0, 0, -1) * actor->getSkeletonNode(elbow)->getMatrix(),
                         osg::Vec3d(0, 0, -1) * expected, 1e-12));
    // The node matrix above the skeleton is actor_m, written by the update.
    EXPECT_EQ(actor->getMatrix(), actor->getActorMatrix());
}

TEST_P(OsgFormats, EverythingTheActorFormatDescribesComesBackAtFullPrecision)
{
    const std::string extension = GetParam();
    osg::ref_ptr<osg::Group> scene = makeScene(false);
    ASSERT_TRUE(scene.valid());
    const std::string path = outFile("precise." + extension);
    ASSERT_TRUE(osgDB::writeNodeFile(*scene, path, fullPrecision().get())) << path;
    osg::ref_ptr<osg::Node> back = osgDB::readRefNodeFile(path, fullPrecision().get());
    ActorNode* actor = actorOf(back.get());
    ASSERT_NE(actor, nullptr) << extension;
    // Definition, geometry, pose and flags, compared as .actor text.
    EXPECT_EQ(asActorText(*actor, "back_" + extension + ".actor"),
              asActorText(*actorOf(scene.get()), "original_" + extension + ".actor"));
}

TEST_P(OsgFormats, EdgeNumbersOfTheActorsOwnFieldsComeBackBitForBitWithoutAPrecisionOption)
{
    // The smallest subnormal, -0, the largest translation an actor holds, 0.1 + 0.2 and its neighbours: each
    // written as its shortest exact text (or raw in .osgb), whatever precision the stream has.
    const std::string extension = GetParam();
    osg::ref_ptr<ActorNode> actor = readActorFile(dataFile("humanoid.actor"));
    ASSERT_TRUE(actor.valid());
    const osg::Vec3d pre(5e-324, -0.0, 1e150);
    const osg::Vec3d post(0.1 + 0.2, -1e-300, -1e150);
    const osg::Quat preRotation(0.30000000000000004, -0.0, 2.2250738585072014e-308, 0.9);
    actor->setPreTranslation(pre);
    actor->setPostTranslation(post);
    actor->setPreRotation(preRotation);
    ASSERT_TRUE(actor->setDof("HumanoidRoot.tz", -2.5e-320));
    const std::string path = outFile("edges." + extension);
    ASSERT_TRUE(osgDB::writeNodeFile(*actor, path));
    osg::ref_ptr<osg::Node> node = osgDB::readRefNodeFile(path);
    const ActorNode* back = dynamic_cast<ActorNode*>(node.get());
    ASSERT_NE(back, nullptr) << extension;
    const auto sameBits = [](double a, double b) { return std::memcmp(&a, &b, sizeof(double)) == 0; };
    for (int i = 0; i < 3; ++i)
    {
        EXPECT_TRUE(sameBits(back->getPreTranslation()[i], pre[i])) << extension << " " << i;
        EXPECT_TRUE(sameBits(back->getPostTranslation()[i], post[i])) << extension << " " << i;
    }
    for (int i = 0; i < 4; ++i)
        EXPECT_TRUE(sameBits(back->getPreRotation()[i], preRotation[i])) << extension << " " << i;
    const int tz = back->getDofIndex("HumanoidRoot.tz");
    ASSERT_GE(tz, 0);
    EXPECT_TRUE(sameBits(back->getDof(unsigned(tz)), -2.5e-320)) << extension;
}

TEST_P(OsgFormats, TheUpdateCallbackAndSkeletonNodesHaveTheirOwnWrappers)
{
    // Each object alone, so that what comes back cannot be a default the ActorNode constructor made.
    const std::string extension = GetParam();
    const std::string callbackPath = outFile("callback." + extension);
    osg::ref_ptr<ActorUpdateCallback> written = new ActorUpdateCallback;
    ASSERT_TRUE(osgDB::writeObjectFile(*written, callbackPath));
    osg::ref_ptr<osg::Object> callback = osgDB::readRefObjectFile(callbackPath);
    EXPECT_NE(dynamic_cast<ActorUpdateCallback*>(callback.get()), nullptr) << extension;

    osg::ref_ptr<SkeletonNode> node = new SkeletonNode(7, "l_wrist");
    node->setHidden(true);
    node->setMatrix(osg::Matrixd::translate(1, 2, 3));
    const std::string nodePath = outFile("skeleton." + extension);
    ASSERT_TRUE(osgDB::writeNodeFile(*node, nodePath));
    osg::ref_ptr<osg::Node> back = osgDB::readRefNodeFile(nodePath);
    const SkeletonNode* skeleton = dynamic_cast<SkeletonNode*>(back.get());
    ASSERT_NE(skeleton, nullptr) << extension;
    EXPECT_EQ(skeleton->getJointIndex(), 7u);
    EXPECT_TRUE(skeleton->getHidden());
    EXPECT_EQ(skeleton->getName(), "l_wrist");
    EXPECT_EQ(skeleton->getMatrix().getTrans(), osg::Vec3d(1, 2, 3));
}

TEST_P(OsgFormats, ABlockedActorComesBackBlockedInItsPose)
{
    const std::string extension = GetParam();
    osg::ref_ptr<osg::Group> scene = makeScene(true);
    ASSERT_TRUE(scene.valid());
    const std::string path = outFile("blocked." + extension);
    ASSERT_TRUE(osgDB::writeNodeFile(*scene, path));
    osg::ref_ptr<osg::Node> back = osgDB::readRefNodeFile(path);
    ActorNode* actor = actorOf(back.get());
    ASSERT_NE(actor, nullptr);
    expectSameActor(*actorOf(scene.get()), *actor, extension + "_blocked");
    const unsigned updates = actor->getNumUpdatesRun();
    runUpdate(*back, 7);
    EXPECT_EQ(actor->getNumUpdatesRun(), updates) << "blocked: the update does nothing";
}

TEST_P(OsgFormats, TrajectoriesComeBackWithTheirPlayersAndKeepMoving)
{
    const std::string extension = GetParam();
    osg::ref_ptr<ActorNode> actor = readActorFile(dataFile("humanoid.actor"));
    ASSERT_TRUE(actor.valid());
    const TrajectoryBuildResult patrol =
        TrajectoryBuilder::build("patrol", {TrajectoryKey{0.0, glm::dvec3(0.0), 0.0},
                                            TrajectoryKey{2.0, glm::dvec3(4.0, 1.0 / 3.0, 0.0), 1.25}});
    const TrajectoryBuildResult later = TrajectoryBuilder::build("later", {TrajectoryKey{0.0, glm::dvec3(1.0), 0.0}});
    ASSERT_TRUE(patrol && later);
    auto playing = std::make_shared<TrajectoryPlayer>(patrol.trajectory);
    playing->setName("on patrol");
    playing->setPlayMode(PlayMode::Loop);
    playing->setSpeed(1.5);
    actor->addController(playing);
    auto waiting = std::make_shared<TrajectoryPlayer>(later.trajectory);
    waiting->setPlayMode(PlayMode::PingPong);
    waiting->pause();
    actor->addController(waiting);
    // A second player of the same path, unnamed: it comes back too, under no name.
    auto again = std::make_shared<TrajectoryPlayer>(patrol.trajectory);
    again->pause();
    actor->addController(again);
    osg::ref_ptr<osg::Group> scene = new osg::Group;
    scene->addChild(actor.get());
    const std::string path = outFile("trajectories." + extension);
    ASSERT_TRUE(osgDB::writeNodeFile(*scene, path, fullPrecision().get())) << path;

    osg::ref_ptr<osg::Node> back = osgDB::readRefNodeFile(path, fullPrecision().get());
    ActorNode* backActor = actorOf(back.get());
    ASSERT_NE(backActor, nullptr) << extension;
    ASSERT_EQ(backActor->getControllers().size(), 3u) << extension;
    auto backPlaying = std::dynamic_pointer_cast<TrajectoryPlayer>(backActor->getControllers()[0]);
    auto backWaiting = std::dynamic_pointer_cast<TrajectoryPlayer>(backActor->getControllers()[1]);
    auto backAgain = std::dynamic_pointer_cast<TrajectoryPlayer>(backActor->getControllers()[2]);
    ASSERT_TRUE(backPlaying && backWaiting && backAgain) << extension;
    EXPECT_EQ(backPlaying->getName(), "on patrol");
    EXPECT_EQ(backWaiting->getName(), "");
    EXPECT_EQ(backAgain->getName(), "");
    EXPECT_EQ(backAgain->getTrajectory(), backPlaying->getTrajectory()) << "one trajectory, two players";
    EXPECT_FALSE(backAgain->isPlaying());
    EXPECT_TRUE(backPlaying->isPlaying());
    EXPECT_EQ(backPlaying->getPlayMode(), PlayMode::Loop);
    EXPECT_EQ(backPlaying->getSpeed(), 1.5);
    EXPECT_FALSE(backWaiting->isPlaying());
    EXPECT_EQ(backWaiting->getPlayMode(), PlayMode::PingPong);
    // The definition's text keeps 12 significant digits, as .actor files do (degrees for the heading).
    const TrajectoryKey& key = backPlaying->getTrajectory()->getKeys().at(1);
    EXPECT_NEAR(key.position.y, 1.0 / 3.0, 1e-12) << extension;
    EXPECT_EQ(key.position.x, 4.0) << extension;
    EXPECT_NEAR(key.heading, 1.25, 1e-11) << extension;

    // The playing one goes on playing: its play head moves as the original's does (speed 1.5, half a second).
    for (unsigned frame : {1u, 31u})
    {
        runUpdate(*scene, frame);
        runUpdate(*back, frame);
    }
    EXPECT_NEAR(backPlaying->getPlayTime(), 0.75, 1e-12) << extension;
    EXPECT_EQ(backPlaying->getPlayTime(), playing->getPlayTime()) << extension;
    EXPECT_EQ(backWaiting->getPlayTime(), 0.0) << extension;
}

INSTANTIATE_TEST_SUITE_P(EveryFormat, OsgFormats, ::testing::Values("osgt", "osgb", "osgx", "osg"),
                         [](const ::testing::TestParamInfo<const char*>& info) { return std::string(info.param); });

// --- broken OSG files: an error, not a half-built actor ---

namespace {

std::string replaced(std::string text, const std::string& from, const std::string& to)
{
    const std::string::size_type at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) text.replace(at, from.size(), to);
    return text;
}

} // namespace

TEST(OsgFormatsBroken, ABrokenDefinitionInOsgtFailsTheRead)
{
    osg::ref_ptr<osg::Group> scene = makeScene(false);
    ASSERT_TRUE(scene.valid());
    ASSERT_TRUE(osgDB::writeNodeFile(*scene, outFile("good.osgt")));
    const std::string good = readTextFile(outFile("good.osgt"));
    const std::string path =
        writeTextFile("broken_definition.osgt",
                      replaced(good, "\"        offset 0 0 0.95\"", "\"        ofset 0 0 0.95\""));
    osgDB::ReaderWriter::ReadResult result = osgDB::Registry::instance()->readNode(path, nullptr);
    EXPECT_FALSE(result.validNode());
    EXPECT_NE(result.message().find("unknown keyword 'ofset' in a joint"), std::string::npos) << result.message();
}

TEST(OsgFormatsBroken, SkeletonNodesThatDoNotMatchTheDefinitionFailTheRead)
{
    osg::ref_ptr<osg::Group> scene = makeScene(false);
    ASSERT_TRUE(scene.valid());
    ASSERT_TRUE(osgDB::writeNodeFile(*scene, outFile("good2.osgt")));
    const std::string good = readTextFile(outFile("good2.osgt"));
    // Two skeleton nodes claim joint 3.
    const std::string path = writeTextFile("broken_skeleton.osgt", replaced(good, "JointIndex 4 ", "JointIndex 3 "));
    osgDB::ReaderWriter::ReadResult result = osgDB::Registry::instance()->readNode(path, nullptr);
    EXPECT_FALSE(result.validNode());
    EXPECT_NE(result.message().find("do not match its definition"), std::string::npos) << result.message();
}

TEST(OsgFormatsBroken, ADofValueThatIsNotANumberInOsgtFailsTheReadNamingTheWord)
{
    osg::ref_ptr<osg::Group> scene = makeScene(false);
    ASSERT_TRUE(scene.valid());
    ASSERT_TRUE(osgDB::writeNodeFile(*scene, outFile("good3.osgt")));
    std::string text = readTextFile(outFile("good3.osgt"));
    const std::size_t dofs = text.find("Dofs ");
    ASSERT_NE(dofs, std::string::npos);
    const std::size_t elbow = text.find(" -1.1 ", dofs); // l_elbow.rx, set by makeScene()
    ASSERT_NE(elbow, std::string::npos) << text.substr(dofs, 400);
    text.replace(elbow, 6, " -1.1x ");
    osgDB::ReaderWriter::ReadResult result =
        osgDB::Registry::instance()->readNode(writeTextFile("broken_dof.osgt", text), nullptr);
    EXPECT_FALSE(result.validNode());
    EXPECT_NE(result.message().find("DOF values of actor 'humanoid': '-1.1x' is not a number"), std::string::npos)
        << result.message();
}

TEST(OsgFormatsBroken, ATransformNumberThatIsNotFiniteOrThatTheActorCannotHoldFailsTheRead)
{
    osg::ref_ptr<osg::Group> scene = makeScene(false);
    ASSERT_TRUE(scene.valid());
    ASSERT_TRUE(osgDB::writeNodeFile(*scene, outFile("good4.osgt")));
    const std::string good = readTextFile(outFile("good4.osgt"));
    ASSERT_NE(good.find("PreTranslation 2.5 -1.25 0"), std::string::npos);
    const struct
    {
        const char* word;
        const char* message;
    } cases[] = {{"1e999", "PreTranslation of actor 'humanoid': '1e999' is not a finite number"},
                 {"nan", "PreTranslation of actor 'humanoid': 'nan' is not a finite number"},
                 {"1e-400", "PreTranslation of actor 'humanoid': '1e-400' is too small for a double"},
                 {"2e150", "PreTranslation of actor 'humanoid' is not one an actor holds"}};
    for (const auto& c : cases)
    {
        const std::string path = writeTextFile("broken_pre.osgt", replaced(good, "PreTranslation 2.5 -1.25 0",
                                                                           "PreTranslation " + std::string(c.word) +
                                                                               " -1.25 0"));
        osgDB::ReaderWriter::ReadResult result = osgDB::Registry::instance()->readNode(path, nullptr);
        EXPECT_FALSE(result.validNode()) << c.word;
        EXPECT_NE(result.message().find(c.message), std::string::npos) << c.word << ": " << result.message();
    }
}

TEST(OsgFormatsBroken, ATransformWordThatIsNotANumberInOsgIsIgnoredAndTheRestIsRead)
{
    // The .osg wrappers warn and go on, as osgDB's own .osg wrappers do with a field they cannot read.
    osg::ref_ptr<osg::Group> scene = makeScene(false);
    ASSERT_TRUE(scene.valid());
    ASSERT_TRUE(osgDB::writeNodeFile(*scene, outFile("good5.osg")));
    const std::string good = readTextFile(outFile("good5.osg"));
    ASSERT_NE(good.find("PreTranslation 2.5 -1.25 0"), std::string::npos);
    const std::string path =
        writeTextFile("broken_pre.osg", replaced(good, "PreTranslation 2.5 -1.25 0", "PreTranslation 2.5 x 0"));
    osg::ref_ptr<osg::Node> back = osgDB::readRefNodeFile(path);
    ActorNode* actor = actorOf(back.get());
    ASSERT_NE(actor, nullptr);
    EXPECT_EQ(actor->getPreTranslation(), osg::Vec3d(0, 0, 0));
    EXPECT_EQ(actor->getPreRotation(), actorOf(scene.get())->getPreRotation());
    const int elbow = actor->getDofIndex("l_elbow.rx");
    ASSERT_GE(elbow, 0);
    EXPECT_EQ(actor->getDof(unsigned(elbow)), -1.1);
}

TEST(OsgFormatsBroken, NamesThatNeedQuotesSurviveEveryFormat)
{
    const std::string path = writeTextFile("quoted_names.actor",
                                           "osgactor 1\nactor \"a \\\"quoted\\\" actor\" {\n joint \"left arm\" {\n"
                                           "  dof rz value 10\n  joint \"hand {x}\"\n }\n}\n");
    osg::ref_ptr<ActorNode> actor = readActorFile(path);
    ASSERT_TRUE(actor.valid());
    ASSERT_EQ(actor->getJointIndex("hand {x}"), 1);
    for (const char* extension : {"osgt", "osgb", "osgx", "osg"})
    {
        const std::string file = outFile(std::string("quoted.") + extension);
        ASSERT_TRUE(osgDB::writeNodeFile(*actor, file));
        osg::ref_ptr<osg::Node> node = osgDB::readRefNodeFile(file);
        ActorNode* back = dynamic_cast<ActorNode*>(node.get());
        ASSERT_NE(back, nullptr) << extension;
        ASSERT_NE(back->getDefinition(), nullptr) << extension;
        EXPECT_EQ(back->getDefinition()->getName(), "a \"quoted\" actor") << extension;
        EXPECT_EQ(back->getJointIndex("left arm"), 0) << extension;
        EXPECT_EQ(back->getJointIndex("hand {x}"), 1) << extension;
        EXPECT_EQ(back->getDof(0u), actor->getDof(0u)) << extension;
    }
}
