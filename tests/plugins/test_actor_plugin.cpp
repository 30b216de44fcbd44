#include "PluginTestUtil"

#include "../nodes/NodeTestUtil"

#include <osgActor/ActorGeometry>
#include <osgActor/ActorUpdateCallback>
#include <osgActor/core/ClipPlayer>
#include <osgActor/core/Trajectory>

#include <osg/ComputeBoundsVisitor>
#include <osg/Geode>
#include <osg/ShapeDrawable>
#include <osgDB/FileUtils>
#include <osgDB/WriteFile>

using namespace osgActor;
using namespace osgActor::test;

namespace {

const double kDegree = osg::PI / 180.0;

} // namespace

TEST(ActorPlugin, TheRegistryFindsOsgdbActorForTheExtension)
{
    osgDB::ReaderWriter* rw = osgDB::Registry::instance()->getReaderWriterForExtension("actor");
    ASSERT_NE(rw, nullptr) << "OSG_LIBRARY_PATH must point at build/lib";
    EXPECT_TRUE(rw->acceptsExtension("actor"));
    EXPECT_EQ(osgDB::Registry::instance()->readNode("no/such/file.actor", nullptr).status(),
              osgDB::ReaderWriter::ReadResult::FILE_NOT_FOUND);
}

TEST(ActorPlugin, ReadsTheHumanoidStandingOnTheFloor)
{
    osg::ref_ptr<ActorNode> actor = readActorFile(dataFile("humanoid.actor"));
    ASSERT_TRUE(actor.valid());
    EXPECT_EQ(actor->getName(), "humanoid");
    ASSERT_EQ(actor->getNumSkeletonNodes(), 18u);
    EXPECT_NE(dynamic_cast<ActorUpdateCallback*>(actor->getUpdateCallback()), nullptr);
    // By hand from the file: pelvis 0.95, hip 0.1 out and 0.05 down, thigh 0.42, shin 0.41.
    EXPECT_TRUE(vec3Near(actor->getJointWorldPosition(actor->getJointIndex("l_ankle")), osg::Vec3d(0.1, 0, 0.07),
                         1e-12));
    EXPECT_TRUE(vec3Near(actor->getJointWorldPosition(actor->getJointIndex("r_wrist")),
                         osg::Vec3d(-0.23, 0, 0.95 + 0.05 + 0.42 - 0.3 - 0.27), 1e-12));
    // The soles touch z = 0 and the head's top is at 1.55 + 0.1 + 0.11 above the pelvis' 0.95 + 0.05.
    osg::ComputeBoundsVisitor bounds;
    actor->accept(bounds);
    EXPECT_NEAR(bounds.getBoundingBox().zMin(), 0.0, 1e-6);
    EXPECT_NEAR(bounds.getBoundingBox().zMax(), 0.95 + 0.05 + 0.55 + 0.1 + 0.11, 1e-6);
    // Geometry hangs below the skeleton nodes as shapes the writer recognises.
    SkeletonNode* head = actor->getSkeletonNode("skullbase");
    ASSERT_NE(head, nullptr);
    unsigned shapes = 0;
    for (unsigned c = 0; c < head->getNumChildren(); ++c)
    {
        GeometryDescription description;
        if (describeGeometryNode(*head->getChild(c), description)) ++shapes;
    }
    EXPECT_EQ(shapes, 3u) << "neck, head and nose";
    // DOF limits arrive in radians.
    const int knee = actor->getDofIndex("l_knee.rx");
    ASSERT_GE(knee, 0);
    EXPECT_NEAR(actor->getDefinition()->getDofMax(static_cast<unsigned>(knee)), 150 * kDegree, 1e-12);
}

TEST(ActorPlugin, TheRobotArmSlidesAlongItsBoom)
{
    osg::ref_ptr<ActorNode> actor = readActorFile(dataFile("robot_arm.actor"));
    ASSERT_TRUE(actor.valid());
    const unsigned wrist = static_cast<unsigned>(actor->getJointIndex("wrist"));
    ASSERT_TRUE(actor->setDof("shoulder.ry", 0.0)); // boom horizontal along X
    ASSERT_TRUE(actor->setDof("boom.tx", 0.1));
    EXPECT_TRUE(vec3Near(actor->getJointWorldPosition(wrist), osg::Vec3d(0.1 + 0.1 + 0.75, 0, 0.65), 1e-12));
    ASSERT_TRUE(actor->setDof("boom.tx", 0.4));
    EXPECT_TRUE(vec3Near(actor->getJointWorldPosition(wrist), osg::Vec3d(0.1 + 0.4 + 0.75, 0, 0.65), 1e-12));
    actor->setDof("boom.tx", 2.0);
    double slide = 0.0;
    ASSERT_TRUE(actor->getDof("boom.tx", slide));
    EXPECT_EQ(slide, 0.45) << "clamped to the file's limit";
}

TEST(ActorPlugin, TheInsectHasSixLegsOfThreeJointsWithFeetOnTheGround)
{
    osg::ref_ptr<ActorNode> actor = readActorFile(dataFile("insect.actor"));
    ASSERT_TRUE(actor.valid());
    EXPECT_EQ(actor->getNumSkeletonNodes(), 1u + 6u * 3u);
    for (const char* side : {"l", "r"})
        for (const char* leg : {"front", "middle", "hind"})
        {
            const std::string tibia = std::string(side) + "_" + leg + "_tibia";
            const int joint = actor->getJointIndex(tibia);
            ASSERT_GE(joint, 0) << tibia;
            // The foot: the tibia's end, 0.37 along its local X (or -X on the right), the centre of a round tip of
            // radius 0.012 that touches the floor.
            const double sign = side[0] == 'l' ? 1.0 : -1.0;
            const osg::Vec3d foot = osg::Vec3d(0.37 * sign, 0, 0) * actor->getJointWorldMatrix(unsigned(joint));
            EXPECT_NEAR(foot.z(), 0.012, 0.0005) << tibia;
        }
}

TEST(ActorPlugin, WritingThenReadingGivesTheSameActorAndTheSameBytes)
{
    for (const char* name : {"humanoid.actor", "insect.actor", "robot_arm.actor"})
    {
        osg::ref_ptr<ActorNode> original = readActorFile(dataFile(name));
        ASSERT_TRUE(original.valid());
        original->setDof(0u, 0.25);
        original->setPreTranslation(osg::Vec3d(1, 2, 0));
        original->setPostRotation(osg::Quat(0.3, osg::Vec3d(0, 0, 1)));
        original->getSkeletonNode(1u)->setHidden(true);
        const std::string first = outFile(std::string("first_") + name);
        ASSERT_TRUE(osgDB::writeNodeFile(*original, first));
        osg::ref_ptr<ActorNode> again = readActorFile(first);
        ASSERT_TRUE(again.valid());
        ASSERT_EQ(again->getNumDofs(), original->getNumDofs());
        for (unsigned d = 0; d < original->getNumDofs(); ++d)
            EXPECT_NEAR(again->getDof(d), original->getDof(d), 1e-11) << name << " DOF " << d;
        EXPECT_TRUE(vec3Near(again->getPreTranslation(), original->getPreTranslation()));
        EXPECT_TRUE(again->getSkeletonNode(1u)->getHidden());
        for (unsigned j = 0; j < original->getNumSkeletonNodes(); ++j)
            EXPECT_TRUE(vec3Near(again->getJointWorldPosition(j), original->getJointWorldPosition(j), 1e-10));
        const std::string second = outFile(std::string("second_") + name);
        ASSERT_TRUE(osgDB::writeNodeFile(*again, second));
        EXPECT_EQ(readTextFile(second), readTextFile(first)) << name;
    }
}

TEST(ActorPlugin, ModelsAreFoundNextToTheActorFileAndWrittenBackAsReferences)
{
    // A model file in a sub-folder, referenced relative to the .actor file, read from elsewhere.
    osgDB::makeDirectory(outFile("models/parts"));
    osg::ref_ptr<osg::Geode> spanner = makeBox(osg::Vec3(0, 0, 0), 0.1f);
    ASSERT_TRUE(osgDB::writeNodeFile(*spanner, outFile("models/parts/spanner.osgt")));
    const std::string path = writeTextFile("models/with_model.actor",
                                           "osgactor 1\nactor a {\n joint hand {\n  model \"parts/spanner.osgt\" {\n"
                                           "   position 0 0 -0.1\n   scale 2\n  }\n }\n}\n");
    osg::ref_ptr<ActorNode> actor = readActorFile(path);
    ASSERT_TRUE(actor.valid());
    SkeletonNode* hand = actor->getSkeletonNode(0u);
    ASSERT_EQ(hand->getNumChildren(), 1u);
    const osg::PositionAttitudeTransform* placed = dynamic_cast<osg::PositionAttitudeTransform*>(hand->getChild(0));
    ASSERT_NE(placed, nullptr);
    EXPECT_EQ(placed->getScale(), osg::Vec3d(2, 2, 2));
    ASSERT_EQ(placed->getNumChildren(), 1u);
    EXPECT_NE(placed->getChild(0)->asGeode(), nullptr) << "the loaded model";
    ASSERT_TRUE(osgDB::writeNodeFile(*actor, outFile("models/with_model_again.actor")));
    const std::string text = readTextFile(outFile("models/with_model_again.actor"));
    EXPECT_NE(text.find("model \"parts/spanner.osgt\" {\n            position 0 0 -0.1\n            scale 2\n"),
              std::string::npos)
        << text;
}

TEST(ActorPlugin, ModelsAreFoundOnTheOptionsDataPath)
{
    osgDB::makeDirectory(outFile("library"));
    ASSERT_TRUE(osgDB::writeNodeFile(*makeBox(osg::Vec3(), 0.2f), outFile("library/wheel.osgt")));
    const std::string path = writeTextFile("uses_library.actor", "osgactor 1\nactor a {\n joint axle {\n"
                                                                  "  model wheel.osgt\n }\n}\n");
    EXPECT_FALSE(osgDB::readRefNodeFile(path).valid()) << "not next to the file, not on the default path";
    osg::ref_ptr<osgDB::Options> options = new osgDB::Options;
    options->getDatabasePathList().push_back(outFile("library"));
    osg::ref_ptr<ActorNode> actor = dynamic_cast<ActorNode*>(osgDB::readRefNodeFile(path, options.get()).get());
    ASSERT_TRUE(actor.valid());
    EXPECT_EQ(actor->getSkeletonNode(0u)->getNumChildren(), 1u);
}

TEST(ActorPlugin, GeometryTheFormatCannotDescribeIsLeftOutOfTheFile)
{
    osg::ref_ptr<ActorNode> actor = readActorFile(dataFile("robot_arm.actor"));
    ASSERT_TRUE(actor.valid());
    osg::ref_ptr<osg::Geode> userGeode = makeBox(osg::Vec3(), 1.0f);
    userGeode->setName("user_box");
    actor->getSkeletonNode("flange")->addChild(userGeode.get());
    const std::string with = outFile("arm_with_user_box.actor");
    ASSERT_TRUE(osgDB::writeNodeFile(*actor, with));
    actor->getSkeletonNode("flange")->removeChild(userGeode.get());
    const std::string without = outFile("arm_without_user_box.actor");
    ASSERT_TRUE(osgDB::writeNodeFile(*actor, without));
    EXPECT_EQ(readTextFile(with), readTextFile(without));
}

TEST(ActorPlugin, ReadsFromAStream)
{
    osgDB::ReaderWriter* rw = osgDB::Registry::instance()->getReaderWriterForExtension("actor");
    ASSERT_NE(rw, nullptr);
    std::istringstream in("osgactor 1\nactor streamed {\n joint a { dof rz value 90 }\n}\n");
    osgDB::ReaderWriter::ReadResult result = rw->readNode(in, nullptr);
    ASSERT_TRUE(result.validNode()) << result.message();
    ActorNode* actor = dynamic_cast<ActorNode*>(result.getNode());
    ASSERT_NE(actor, nullptr);
    EXPECT_NEAR(actor->getDof(0u), osg::PI_2, 1e-15);
    std::istringstream broken("osgactor 1\nactor a {\n joint a { dof rz value x }\n}\n");
    result = rw->readNode(broken, nullptr);
    EXPECT_FALSE(result.validNode());
    EXPECT_EQ(result.message(), "<stream>:3: 'x' is not a number");
}

TEST(ActorPlugin, WritingAScenePicksItsOneActor)
{
    osg::ref_ptr<osg::Group> root = new osg::Group;
    EXPECT_FALSE(osgDB::writeNodeFile(*root, outFile("empty.actor")));
    osg::ref_ptr<ActorNode> actor = readActorFile(dataFile("robot_arm.actor"));
    ASSERT_TRUE(actor.valid());
    root->addChild(actor.get());
    EXPECT_TRUE(osgDB::writeNodeFile(*root, outFile("scene.actor")));
    root->addChild(osg::clone(actor.get()));
    osgDB::ReaderWriter* rw = osgDB::Registry::instance()->getReaderWriterForExtension("actor");
    ASSERT_NE(rw, nullptr);
    const osgDB::ReaderWriter::WriteResult result = rw->writeNode(*root, outFile("two.actor"), nullptr);
    EXPECT_FALSE(result.success());
    EXPECT_EQ(result.message(), "a .actor file holds exactly one actor; the scene has 2");
}

TEST(ActorPlugin, ClipsComeWithTheActorPlayAndSurviveOsgFormats)
{
    const std::string path = writeTextFile("with_clip.actor", R"(osgactor 1
actor waver {
    joint shoulder {
        dof rz min -90 max 90
        joint hand { offset 1 0 0 }
    }
    clip wave {
        channel shoulder.rz {
            key 0 0
            key 1 90
        }
    }
}
)");
    osg::ref_ptr<ActorNode> actor = readActorFile(path);
    ASSERT_TRUE(actor.valid());
    ASSERT_NE(actor->getClipLibrary(), nullptr);
    ClipPtr wave = actor->getClipLibrary()->getClip("wave");
    ASSERT_NE(wave, nullptr);
    // Played by the nodekit's own clip player: at 0.5 s the shoulder is half way, 45 degrees.
    std::shared_ptr<ClipPlayer> player = std::make_shared<ClipPlayer>(wave);
    player->seek(0.5);
    player->pause();
    actor->addController(player);
    runUpdate(*actor, 1);
    EXPECT_NEAR(actor->getDof(0u), osg::PI_4, 1e-12);
    EXPECT_TRUE(vec3Near(actor->getJointWorldPosition(1u), osg::Vec3d(std::sqrt(0.5), std::sqrt(0.5), 0), 1e-12));

    // The clip library goes through .osgt and .osg with the definition, and back into .actor text unchanged.
    ASSERT_TRUE(osgDB::writeNodeFile(*actor, outFile("clip_first.actor")));
    for (const char* extension : {"osgt", "osgb", "osg"})
    {
        const std::string file = outFile(std::string("with_clip.") + extension);
        ASSERT_TRUE(osgDB::writeNodeFile(*actor, file));
        osg::ref_ptr<ActorNode> back = dynamic_cast<ActorNode*>(osgDB::readRefNodeFile(file).get());
        ASSERT_TRUE(back.valid()) << extension;
        ASSERT_NE(back->getClipLibrary(), nullptr) << extension;
        EXPECT_EQ(back->getClipLibrary()->getClipNames(), std::vector<std::string>{"wave"}) << extension;
        const std::string again = outFile(std::string("clip_again_") + extension + ".actor");
        ASSERT_TRUE(osgDB::writeNodeFile(*back, again));
        EXPECT_EQ(readTextFile(again), readTextFile(outFile("clip_first.actor"))) << extension;
    }
    EXPECT_NE(readTextFile(outFile("clip_first.actor")).find("    clip wave {\n        channel shoulder.rz {\n"
                                                             "            key 0 0\n            key 1 90\n"),
              std::string::npos);
}

TEST(ActorPlugin, APlayStatementStartsTheClipAndItsPlayerIsWrittenBack)
{
    const std::string text = R"(osgactor 1
actor waver {
    joint shoulder {
        dof rz min -90 max 90
        joint hand { offset 1 0 0 }
    }
    clip wave {
        play pingpong
        channel shoulder.rz {
            key 0 0
            key 1 90
        }
    }
}
)";
    osg::ref_ptr<ActorNode> actor = readActorFile(writeTextFile("playing.actor", text));
    ASSERT_TRUE(actor.valid());
    auto player = std::dynamic_pointer_cast<ClipPlayer>(actor->findController("wave"));
    ASSERT_TRUE(player) << "the clip plays on load";
    EXPECT_TRUE(player->isPlaying());
    EXPECT_EQ(player->getPlayMode(), PlayMode::PingPong);
    // Frame n of runUpdate is at n / 60 s: 1.5 s into a ping-pong of a 1 s clip is half way back, 45 degrees.
    runUpdate(*actor, 1);
    runUpdate(*actor, 91);
    EXPECT_NEAR(actor->getDof(0u), osg::PI_4, 1e-9);
    // Written back as the player it made, play head included, and stable from then on.
    ASSERT_TRUE(osgDB::writeNodeFile(*actor, outFile("playing_once.actor")));
    const std::string written = readTextFile(outFile("playing_once.actor"));
    EXPECT_NE(written.find("    player wave {\n        clip wave\n        play pingpong\n        time 1.5\n    }\n"),
              std::string::npos)
        << written;
    EXPECT_EQ(written.find("        play pingpong\n        channel"), std::string::npos) << "no second player";
    osg::ref_ptr<ActorNode> back = readActorFile(outFile("playing_once.actor"));
    ASSERT_TRUE(back.valid());
    ASSERT_TRUE(osgDB::writeNodeFile(*back, outFile("playing_twice.actor")));
    EXPECT_EQ(readTextFile(outFile("playing_twice.actor")), written);
}

TEST(ActorPlugin, AnUnknownPlayModeIsAnErrorWithItsLine)
{
    const std::string path = writeTextFile("bad_play.actor", "osgactor 1\nactor a {\n    joint b { dof rx }\n"
                                                             "    clip c {\n        play sideways\n"
                                                             "        channel b.rx { key 0 0 }\n    }\n}\n");
    osgDB::ReaderWriter::ReadResult read = osgDB::Registry::instance()->readNode(path, nullptr);
    EXPECT_FALSE(read.validNode());
    EXPECT_NE(read.message().find("bad_play.actor:5: 'sideways' is not a play mode"), std::string::npos)
        << read.message();
}

TEST(ActorPlugin, ATrajectoryMovesTheActorAlongItsPathAndItsPlayerIsWrittenBack)
{
    const std::string text = R"(osgactor 1
actor walker {
    joint hips { dof rz }
    trajectory patrol {
        play loop
        key 0 0 0 0 0
        key 2 4 0 0 90
    }
}
)";
    osg::ref_ptr<ActorNode> actor = readActorFile(writeTextFile("trajectory.actor", text));
    ASSERT_TRUE(actor.valid());
    auto player = std::dynamic_pointer_cast<TrajectoryPlayer>(actor->findController("patrol"));
    ASSERT_TRUE(player) << "a player named after the trajectory";
    EXPECT_TRUE(player->isPlaying());
    EXPECT_EQ(player->getPlayMode(), PlayMode::Loop);
    // Frame n of runUpdate is at n / 60 s: one second in, half way along, turned 45 degrees; 2.5 s in, a loop and
    // a quarter.
    runUpdate(*actor, 1);
    runUpdate(*actor, 61);
    EXPECT_TRUE(vec3Near(actor->getPreTranslation(), osg::Vec3d(2, 0, 0), 1e-9));
    const osg::Vec3d facing = actor->getPreRotation() * osg::Vec3d(1, 0, 0);
    EXPECT_TRUE(vec3Near(facing, osg::Vec3d(std::cos(osg::PI_4), std::sin(osg::PI_4), 0), 1e-9));
    runUpdate(*actor, 151);
    EXPECT_TRUE(vec3Near(actor->getPreTranslation(), osg::Vec3d(1, 0, 0), 1e-9));

    ASSERT_TRUE(osgDB::writeNodeFile(*actor, outFile("trajectory_once.actor")));
    const std::string written = readTextFile(outFile("trajectory_once.actor"));
    // The keys in the trajectory, the player that the trajectory's play statement made in a player section.
    EXPECT_NE(written.find("    trajectory patrol {\n        key 0 0 0 0 0\n        key 2 4 0 0 90\n    }\n"
                           "    player patrol {\n        trajectory patrol\n        play loop\n        time 2.5\n"
                           "    }\n"),
              std::string::npos)
        << written;
    osg::ref_ptr<ActorNode> back = readActorFile(outFile("trajectory_once.actor"));
    ASSERT_TRUE(back.valid());
    ASSERT_TRUE(osgDB::writeNodeFile(*back, outFile("trajectory_twice.actor")));
    EXPECT_EQ(readTextFile(outFile("trajectory_twice.actor")), written);
}

TEST(ActorPlugin, ATrajectoryReadFromACsvFileBesideTheActorFile)
{
    osgDB::makeDirectory(outFile("trajectory_csv/paths"));
    std::ofstream(outFile("trajectory_csv/paths/dash.csv")) << "time,x,y,z,heading\n0,0,0,0,0\n1,2,0,0,0\n"
                                                               "2,2,2,0,90\n";
    const std::string actorText = "osgactor 1\nactor a {\n    joint b { dof rz }\n    trajectory dash {\n"
                                  "        play once\n        speed 2\n        file \"paths/dash.csv\"\n    }\n}\n";
    std::ofstream(outFile("trajectory_csv/runner.actor")) << actorText;
    osg::ref_ptr<ActorNode> actor = readActorFile(outFile("trajectory_csv/runner.actor"));
    ASSERT_TRUE(actor.valid());
    auto player = std::dynamic_pointer_cast<TrajectoryPlayer>(actor->findController("dash"));
    ASSERT_TRUE(player);
    EXPECT_EQ(player->getSpeed(), 2.0);
    ASSERT_EQ(player->getTrajectory()->getKeys().size(), 3u);
    EXPECT_EQ(player->getTrajectory()->getName(), "dash");
    // At speed 2, 0.75 s of frames is 1.5 s of the path: half way up the left turn.
    runUpdate(*actor, 1);
    runUpdate(*actor, 46);
    EXPECT_TRUE(vec3Near(actor->getPreTranslation(), osg::Vec3d(2, 1, 0), 1e-9));

    // A missing file fails the read at the trajectory's line.
    std::ofstream(outFile("trajectory_csv/lost.actor"))
        << "osgactor 1\nactor a {\n    joint b { dof rz }\n    trajectory dash { file \"paths/nowhere.csv\" }\n}\n";
    osgDB::ReaderWriter::ReadResult read =
        osgDB::Registry::instance()->readNode(outFile("trajectory_csv/lost.actor"), nullptr);
    EXPECT_FALSE(read.validNode());
    EXPECT_NE(read.message().find("lost.actor:4: trajectory 'dash': cannot find the file 'paths/nowhere.csv'"),
              std::string::npos)
        << read.message();
}
