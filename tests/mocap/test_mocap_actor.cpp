#include "MocapActorCheck"

#include <osgActor/MocapActor>
#include <osgActor/StickFigure>
#include <osgActor/mocap/AsfReader>

#include <osg/Geode>

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

using namespace osgActor;
using namespace osgActor::test;

namespace {

double distance(const osg::Vec3d& a, const osg::Vec3d& b) { return (a - b).length(); }

} // namespace

TEST(MocapActor, RefusesMissingAndUnknownFilesAndAnAsfWithoutMotion)
{
    std::string error;
    EXPECT_FALSE(readMocapActor("/nonexistent/walk.bvh", MocapActorOptions(), error).valid());
    EXPECT_NE(error.find("/nonexistent/walk.bvh: cannot open"), std::string::npos) << error;
    EXPECT_FALSE(readMocapActor("walk.fbx", MocapActorOptions(), error).valid());
    EXPECT_NE(error.find("expected .bvh or .asf"), std::string::npos) << error;

    const std::filesystem::path folder = std::filesystem::path(OSGACTOR_TEST_BINARY_DIR) / "lonely";
    std::filesystem::create_directories(folder);
    std::ofstream(folder / "stick.asf")
        << ":root\n order TX TY TZ RX RY RZ\n axis XYZ\n:bonedata\n:hierarchy\n begin\n end\n";
    EXPECT_FALSE(readMocapActor((folder / "stick.asf").string(), MocapActorOptions(), error).valid());
    EXPECT_NE(error.find("no AMC motion given and none found beside it"), std::string::npos) << error;

    std::ofstream(folder / "broken.bvh") << "HIERARCHY\nROOT hips\n{\n  OFFSET 0 0\n}\n";
    EXPECT_FALSE(readMocapActor((folder / "broken.bvh").string(), MocapActorOptions(), error).valid());
    EXPECT_NE(error.find("broken.bvh:5: "), std::string::npos) << error;
}

TEST(MocapActor, FindsTheAmcBesideAnAsf)
{
    EXPECT_EQ(findAmcBeside(repositoryMocap("asfamc/11.asf")), repositoryMocap("asfamc/11_01.amc"));
    EXPECT_EQ(findAmcBeside(repositoryMocap("asfamc/charleston.asf")), repositoryMocap("asfamc/charleston1.amc"));
}

TEST(MocapActor, PlaysABvhFileFromTheFrameStamp)
{
    const std::string path = repositoryMocap("bvh/12_03.bvh");
    std::string error;
    osg::ref_ptr<ActorNode> actor = readMocapActor(path, MocapActorOptions(), error);
    ASSERT_TRUE(actor.valid()) << error;
    ASSERT_TRUE(actor->findController("mocap"));
    ASSERT_TRUE(actor->getClipLibrary());
    EXPECT_TRUE(actor->getClipLibrary()->getClip("12_03"));

    // Frame n of runUpdate is clip frame 2n of this 120 Hz file; the end sites are joints too.
    expectToFollowBvh(*actor, path, {0u, 1u, 2u, 7u}, true);
}

TEST(MocapActor, PlaysAnAsfAmcPairFoundBesideEachOther)
{
    const std::string asfPath = repositoryMocap("asfamc/11.asf");
    std::string error;
    osg::ref_ptr<ActorNode> actor = readMocapActor(asfPath, MocapActorOptions(), error);
    ASSERT_TRUE(actor.valid()) << error;
    expectToFollowAsfAmc(*actor, asfPath, repositoryMocap("asfamc/11_01.amc"), 1.0);
}

TEST(StickFigure, HangsABallOnEveryJointAndBonesOnParents)
{
    std::string error;
    osg::ref_ptr<ActorNode> actor = readMocapActor(repositoryMocap("bvh/12_03.bvh"), MocapActorOptions(), error);
    ASSERT_TRUE(actor.valid()) << error;
    const osg::Node* ball = nullptr;
    for (unsigned j = 0; j < actor->getNumSkeletonNodes(); ++j)
    {
        const SkeletonNode* node = actor->getSkeletonNode(j);
        const osg::Geode* first = nullptr;
        unsigned bones = 0;
        for (unsigned c = 0; c < node->getNumChildren(); ++c)
        {
            const osg::Geode* geode = dynamic_cast<const osg::Geode*>(node->getChild(c));
            if (!geode) continue;
            if (geode->getName() == "joint ball") first = geode;
            if (geode->getName() == "bones") ++bones;
        }
        ASSERT_NE(first, nullptr) << node->getName();
        if (ball)
        {
            EXPECT_EQ(first, ball) << "one ball shared by every joint";
        }
        ball = first;
        const bool hasChildJoints = node->getNumChildren() > 1u + bones;
        EXPECT_EQ(bones, hasChildJoints ? 1u : 0u) << node->getName();
    }
    EXPECT_TRUE(actor->getBound().valid());
}

TEST(MocapActor, ClonesShareTheClipLibraryButPlayOnTheirOwn)
{
    std::string error;
    osg::ref_ptr<ActorNode> actor = readMocapActor(repositoryMocap("bvh/12_03.bvh"), MocapActorOptions(), error);
    ASSERT_TRUE(actor.valid()) << error;
    osg::ref_ptr<ActorNode> twin = osg::clone(actor.get(), osg::CopyOp::SHALLOW_COPY);
    EXPECT_EQ(twin->getClipLibrary(), actor->getClipLibrary());
    auto twinPlayer = std::dynamic_pointer_cast<ClipPlayer>(twin->findController("mocap"));
    ASSERT_TRUE(twinPlayer);
    EXPECT_NE(twinPlayer, actor->findController("mocap"));
    twinPlayer->pause();
    osg::ref_ptr<osg::Group> root = new osg::Group;
    root->addChild(actor.get());
    root->addChild(twin.get());
    runUpdate(*root, 0);
    runUpdate(*root, 30);
    const unsigned hand = static_cast<unsigned>(actor->getJointIndex("LeftHand"));
    EXPECT_GT(distance(actor->getJointWorldPosition(hand), twin->getJointWorldPosition(hand)), 1e-3)
        << "the paused twin stayed behind";
}

TEST(MocapOptionString, RefusesBadValuesOfKnownWords)
{
    MocapActorOptions options;
    std::string error;
    EXPECT_FALSE(parseMocapOptionString("scale=abc", options, error));
    EXPECT_NE(error.find("scale needs a positive number"), std::string::npos) << error;
    EXPECT_FALSE(parseMocapOptionString("fps=-3", options, error));
    EXPECT_FALSE(parseMocapOptionString("up=X", options, error));
    EXPECT_NE(error.find("up must be y or z, not 'X'"), std::string::npos) << error;
    EXPECT_FALSE(parseMocapOptionString("mode=forever", options, error));
    EXPECT_NE(error.find("mode must be once, loop or pingpong"), std::string::npos) << error;
    EXPECT_FALSE(parseMocapOptionString("rootMotion=sideways", options, error));
    EXPECT_NE(error.find("rootMotion must be in_skeleton, to_transforms or in_place"), std::string::npos) << error;
    EXPECT_FALSE(parseMocapOptionString("scale=1e999", options, error)) << "not finite";
    EXPECT_FALSE(parseMocapOptionString("scale=1,5", options, error)) << "numbers do not follow the locale";
}

TEST(MocapOptionString, ReadsEveryOptionAndLeavesOtherWordsAlone)
{
    MocapActorOptions options;
    std::string error;
    ASSERT_TRUE(parseMocapOptionString("amc=11_01.amc scale=0.5 up=z fps=60 dropFirstFrame absoluteRoot limits "
                                       "mode=pingpong rootMotion=in_place noFigure noRotation",
                                       options, error))
        << error;
    EXPECT_EQ(options.amcFile, "11_01.amc");
    EXPECT_DOUBLE_EQ(options.scale, 0.5);
    EXPECT_EQ(options.fileUpAxis, UpAxis::Z);
    EXPECT_DOUBLE_EQ(options.amcFrameRate, 60.0);
    EXPECT_TRUE(options.dropFirstFrame);
    EXPECT_TRUE(options.absoluteRootPosition);
    EXPECT_TRUE(options.applyAsfLimits);
    EXPECT_EQ(options.playMode, PlayMode::PingPong);
    EXPECT_EQ(options.rootMotion, RootMotion::InPlace);
    EXPECT_FALSE(options.addFigure);
}

TEST(MocapOptionString, UsesTheWordsOfTheActorFormatAndStillReadsTheOldOnes)
{
    // One vocabulary: the option values are the .actor format's words for the same enums.
    for (const RootMotion mode : {RootMotion::InSkeleton, RootMotion::ToTransforms, RootMotion::InPlace})
    {
        MocapActorOptions options;
        std::string error;
        ASSERT_TRUE(parseMocapOptionString(std::string("rootMotion=") + rootMotionName(mode), options, error)) << error;
        EXPECT_EQ(options.rootMotion, mode);
    }
    for (const UpAxis axis : {UpAxis::Y, UpAxis::Z})
    {
        MocapActorOptions options;
        std::string error;
        ASSERT_TRUE(parseMocapOptionString(std::string("up=") + upAxisName(axis), options, error)) << error;
        EXPECT_EQ(options.fileUpAxis, axis);
    }
    // Earlier versions' words, deprecated, still mean what they meant.
    MocapActorOptions options;
    std::string error;
    ASSERT_TRUE(parseMocapOptionString("up=Z rootMotion=transforms", options, error)) << error;
    EXPECT_EQ(options.fileUpAxis, UpAxis::Z);
    EXPECT_EQ(options.rootMotion, RootMotion::ToTransforms);
    ASSERT_TRUE(parseMocapOptionString("rootMotion=skeleton", options, error)) << error;
    EXPECT_EQ(options.rootMotion, RootMotion::InSkeleton);
    ASSERT_TRUE(parseMocapOptionString("rootMotion=inplace", options, error)) << error;
    EXPECT_EQ(options.rootMotion, RootMotion::InPlace);
}

TEST(MocapActor, StartsItsClipAtTheFirstFrameStampItSees)
{
    const std::string path = repositoryMocap("bvh/12_03.bvh");
    std::string error;
    osg::ref_ptr<ActorNode> actor = readMocapActor(path, MocapActorOptions(), error);
    ASSERT_TRUE(actor.valid()) << error;
    const reference::Bvh bvh = reference::readBvh(path);
    const double size = extent(reference::bvhPositions(bvh, 0));
    const unsigned hips = static_cast<unsigned>(actor->getJointIndex("Hips"));
    // Posed at frame 0 before any update, then still frame 0 when the scene is already 10 s old, then 2 frames on.
    EXPECT_LT(distance(actor->getJointWorldPosition(hips), zUp(reference::bvhPositions(bvh, 0)[0])), 1e-6 * size);
    osg::ref_ptr<osg::Group> root = new osg::Group;
    root->addChild(actor.get());
    runUpdate(*root, 600);
    EXPECT_LT(distance(actor->getJointWorldPosition(hips), zUp(reference::bvhPositions(bvh, 0)[0])), 1e-6 * size);
    runUpdate(*root, 601);
    EXPECT_LT(distance(actor->getJointWorldPosition(hips), zUp(reference::bvhPositions(bvh, 2)[0])), 1e-6 * size);
}
