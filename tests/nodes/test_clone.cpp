#include "NodeTestUtil"

using namespace osgActor;
using namespace osgActor::test;

TEST(CloneActor, ShallowCloneIsAnIndependentInstanceSharingDefinitionAndGeometry)
{
    osg::ref_ptr<ActorNode> original = new ActorNode(makePlanarArm());
    osg::ref_ptr<osg::Geode> hand = makeBox(osg::Vec3(), 0.2f);
    original->getSkeletonNode("tip")->addChild(hand.get());
    original->setDof("base.rz", 0.25);
    original->setPreTranslation(osg::Vec3d(1, 2, 3));

    osg::ref_ptr<ActorNode> copy = osg::clone(original.get(), osg::CopyOp::SHALLOW_COPY);
    ASSERT_EQ(copy->getNumSkeletonNodes(), original->getNumSkeletonNodes());
    EXPECT_EQ(copy->getDefinition(), original->getDefinition()) << "the definition is shared";
    EXPECT_EQ(copy->getDofs(), original->getDofs()) << "the pose is copied";
    EXPECT_EQ(copy->getPreTranslation(), original->getPreTranslation());
    for (unsigned j = 0; j < copy->getNumSkeletonNodes(); ++j)
    {
        EXPECT_NE(copy->getSkeletonNode(j), original->getSkeletonNode(j)) << "skeleton nodes are the instance's";
        EXPECT_EQ(copy->getSkeletonNode(j)->getJointIndex(), j);
    }
    ASSERT_EQ(copy->getSkeletonNode("tip")->getNumChildren(), 1u);
    EXPECT_EQ(copy->getSkeletonNode("tip")->getChild(0), hand.get()) << "geometry is shared";
    EXPECT_EQ(hand->getNumParents(), 2u);

    // They move independently.
    copy->setDof("base.rz", osg::PI_2);
    runUpdate(*original, 1);
    runUpdate(*copy, 1);
    EXPECT_EQ(original->getDof(0u), 0.25);
    EXPECT_TRUE(vec3Near(copy->getJointWorldPosition(3), osg::Vec3d(1, 4.5, 3), 1e-14));
    EXPECT_TRUE(vec3Near(original->getJointWorldPosition(3),
                         osg::Vec3d(1 + 2.5 * std::cos(0.25), 2 + 2.5 * std::sin(0.25), 3), 1e-14));
    EXPECT_NE(copy->getSkeletonNode(0u)->getMatrix(), original->getSkeletonNode(0u)->getMatrix());
}

TEST(CloneActor, DeepCloneCopiesGeometryToo)
{
    osg::ref_ptr<ActorNode> original = new ActorNode(makePlanarArm());
    osg::ref_ptr<osg::Geode> hand = makeBox(osg::Vec3(), 0.2f);
    original->getSkeletonNode("tip")->addChild(hand.get());
    osg::ref_ptr<ActorNode> copy = osg::clone(original.get(), osg::CopyOp::DEEP_COPY_ALL);
    ASSERT_EQ(copy->getSkeletonNode("tip")->getNumChildren(), 1u);
    EXPECT_NE(copy->getSkeletonNode("tip")->getChild(0), hand.get());
    EXPECT_EQ(copy->getDefinition(), original->getDefinition()) << "even a deep copy shares the definition";
}

TEST(CloneActor, CloneHasItsOwnUpdateCallbackBehaviour)
{
    osg::ref_ptr<ActorNode> original = new ActorNode(makePlanarArm());
    osg::ref_ptr<ActorNode> copy = osg::clone(original.get(), osg::CopyOp::SHALLOW_COPY);
    ASSERT_NE(copy->getUpdateCallback(), nullptr);
    copy->setDof("lower.rz", 0.5);
    runUpdate(*copy, 1);
    EXPECT_EQ(copy->getNumUpdatesRun(), 1u);
    EXPECT_EQ(original->getNumUpdatesRun(), 0u);
    EXPECT_TRUE(original->getSkeletonNode(2u)->getMatrix().getRotate().zeroRotation());
}

TEST(CloneActor, RebindRefusesAMismatchedSkeleton)
{
    osg::ref_ptr<ActorNode> actor = new ActorNode(makePlanarArm());
    actor->getSkeletonNode("tip")->setJointIndex(1); // two nodes now claim joint 1, none joint 3
    EXPECT_FALSE(actor->rebindSkeletonNodes());
    EXPECT_EQ(actor->getNumSkeletonNodes(), 0u);
    runUpdate(*actor, 1); // no crash with an empty list
}
