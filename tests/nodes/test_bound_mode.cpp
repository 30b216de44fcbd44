// ActorNode::BOUND_COVERS_ROTATIONS: each skeleton node that only rotates has a ball about its joint that holds its
// subtree in every rotation, so turning it dirties no bound; joints that translate keep bounds that follow the pose.
#include "NodeTestUtil"

#include <osgActor/ActorSceneIO>
#include <osgActor/SkeletonNode>
#include <osgActor/io/ActorReader>

#include <osg/io_utils>
#include <osgUtil/IntersectionVisitor>
#include <osgUtil/LineSegmentIntersector>

#include <cmath>
#include <sstream>
#include <random>

using namespace osgActor;
using namespace osgActor::test;

namespace {

/** Counts how often OSG recomputes a node's bound (Node::getBound() calls it only when the bound is dirty). */
class CountingBound : public osg::Node::ComputeBoundingSphereCallback
{
public:
    osg::BoundingSphere computeBound(const osg::Node& node) const override
    {
        ++count;
        return node.computeBound();
    }
    mutable int count = 0;
};

CountingBound* countBounds(osg::Node& node)
{
    osg::ref_ptr<CountingBound> counter = new CountingBound;
    node.setComputeBoundingSphereCallback(counter.get());
    return counter.get();
}

/** Stands for a hand: a node whose only bound is a sphere of radius 0.1 about its origin. */
osg::ref_ptr<osg::Group> makeHand()
{
    osg::ref_ptr<osg::Group> hand = new osg::Group;
    hand->setInitialBound(osg::BoundingSphere(osg::Vec3(), 0.1f));
    return hand;
}

/** The planar arm (base 0, upper 1, lower 2, tip 3) with a hand at its tip, its bounds covering rotations. */
osg::ref_ptr<ActorNode> makeCoveredArm()
{
    osg::ref_ptr<ActorNode> actor = new ActorNode(makePlanarArm());
    actor->getSkeletonNode(3u)->addChild(makeHand().get());
    actor->setBoundMode(ActorNode::BOUND_COVERS_ROTATIONS);
    return actor;
}

/** The actor a builder of three joints describes, with a hand on the third, its bounds covering rotations. */
osg::ref_ptr<ActorNode> makeCoveredActor(ActorDefinitionBuilder& builder)
{
    const BuildResult built = builder.build();
    EXPECT_TRUE(built) << built.error;
    if (!built) return nullptr;
    osg::ref_ptr<ActorNode> actor = new ActorNode(built.definition);
    actor->getSkeletonNode(2u)->addChild(makeHand().get());
    actor->setBoundMode(ActorNode::BOUND_COVERS_ROTATIONS);
    return actor;
}

::testing::AssertionResult sphereNear(const osg::BoundingSphere& actual, const osg::Vec3d& centre, double radius)
{
    // Bounding spheres are single precision in Debian's OSG.
    if (vec3Near(actual.center(), centre, 1e-6) && std::abs(actual.radius() - radius) <= 1e-6)
        return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << "centre " << actual.center() << " radius " << actual.radius();
}

} // namespace

TEST(BoundMode, CoversRotationsByDefault)
{
    osg::ref_ptr<ActorNode> actor = new ActorNode(makePlanarArm());
    EXPECT_EQ(actor->getBoundMode(), ActorNode::BOUND_COVERS_ROTATIONS);
    // base, upper and lower turn about Z; the tip has no DOF, so its bound follows (and never moves).
    for (unsigned j = 0; j < 3; ++j) EXPECT_TRUE(actor->getSkeletonNode(j)->getBoundCoversRotations()) << j;
    EXPECT_FALSE(actor->getSkeletonNode(3u)->getBoundCoversRotations());
    actor->setBoundMode(ActorNode::BOUND_FOLLOWS_POSE);
    for (unsigned j = 0; j < actor->getNumSkeletonNodes(); ++j)
        EXPECT_FALSE(actor->getSkeletonNode(j)->getBoundCoversRotations()) << j;
}

TEST(BoundMode, EachRotatingJointGetsABallAboutItsCentreHandDerived)
{
    osg::ref_ptr<ActorNode> actor = makeCoveredArm();
    // The tip has no DOF: its bound follows (and never moves): the hand's sphere, 0.5 along X in lower's frame.
    EXPECT_FALSE(actor->getSkeletonNode(3u)->getBoundCoversRotations());
    EXPECT_TRUE(sphereNear(actor->getSkeletonNode(3u)->getBound(), osg::Vec3d(0.5, 0, 0), 0.1));
    // lower, at (1,0,0) in upper's frame, reaches 0.5 + 0.1; upper, at (1,0,0) in base's frame, reaches 1 + 0.6;
    // base, at the origin, reaches 1 + 1.6.
    EXPECT_TRUE(sphereNear(actor->getSkeletonNode(2u)->getBound(), osg::Vec3d(1, 0, 0), 0.6));
    EXPECT_TRUE(sphereNear(actor->getSkeletonNode(1u)->getBound(), osg::Vec3d(1, 0, 0), 1.6));
    EXPECT_TRUE(sphereNear(actor->getSkeletonNode(0u)->getBound(), osg::Vec3d(0, 0, 0), 2.6));
    EXPECT_TRUE(sphereNear(actor->getBound(), osg::Vec3d(0, 0, 0), 2.6));
    // Back to following the pose: the bound is the hand's sphere again, at the tip.
    actor->setBoundMode(ActorNode::BOUND_FOLLOWS_POSE);
    EXPECT_FALSE(actor->getSkeletonNode(0u)->getBoundCoversRotations());
    EXPECT_TRUE(sphereNear(actor->getBound(), osg::Vec3d(2.5, 0, 0), 0.1));
}

TEST(BoundMode, TurningJointsRecomputesNoBoundYetTheBallHoldsEveryPose)
{
    osg::ref_ptr<ActorNode> actor = makeCoveredArm();
    std::vector<CountingBound*> counters;
    for (unsigned j = 0; j < 3; ++j) counters.push_back(countBounds(*actor->getSkeletonNode(j)));
    CountingBound* actorCounter = countBounds(*actor);
    const osg::BoundingSphere first = actor->getBound();
    std::mt19937 random(7);
    std::uniform_real_distribution<double> angle(-2.0, 2.0);
    for (unsigned frame = 1; frame <= 20; ++frame)
    {
        ASSERT_TRUE(actor->setDofs({angle(random), angle(random), angle(random)}));
        runUpdate(*actor, frame);
        const osg::BoundingSphere bound = actor->getBound();
        EXPECT_EQ(bound.center(), first.center());
        EXPECT_EQ(bound.radius(), first.radius());
        // The hand, wherever the pose puts it, lies inside.
        const osg::Vec3d hand = actor->getJointWorldPosition(3);
        EXPECT_LE((hand - osg::Vec3d(bound.center())).length() + 0.1, bound.radius() + 1e-6) << "frame " << frame;
    }
    for (unsigned j = 0; j < 3; ++j) EXPECT_EQ(counters[j]->count, 1) << "joint " << j << " was recomputed";
    EXPECT_EQ(actorCounter->count, 1);

    // The same frames following the pose recompute every moving joint's bound each time.
    actor->setBoundMode(ActorNode::BOUND_FOLLOWS_POSE);
    actor->getBound();
    const int before = counters[2]->count;
    for (unsigned frame = 21; frame <= 25; ++frame)
    {
        ASSERT_TRUE(actor->setDofs({angle(random), angle(random), angle(random)}));
        runUpdate(*actor, frame);
        actor->getBound();
    }
    EXPECT_EQ(counters[2]->count, before + 5);
}

TEST(BoundMode, AJointWhoseOffsetAlsoTurnsKeepsItsBallToo)
{
    // An offset with a rotation (as ASF bone axes give) still keeps the joint's centre where it is.
    ActorDefinitionBuilder b("tilted");
    b.addJoint("base").dofs(Dof::RX | Dof::RZ);
    b.addJoint("arm", "base").offset(1, 0.5, -0.25).rotation(0.7, 0.3, -0.5, 0.8).dofs(Dof::RX | Dof::RY);
    b.addJoint("hand", "arm").offset(1, 0, 0);
    osg::ref_ptr<ActorNode> actor = makeCoveredActor(b);
    ASSERT_TRUE(actor.valid());
    CountingBound* arm = countBounds(*actor->getSkeletonNode(1u));
    EXPECT_TRUE(sphereNear(actor->getSkeletonNode(1u)->getBound(), osg::Vec3d(1, 0.5, -0.25), 1.1));
    for (unsigned frame = 1; frame <= 5; ++frame)
    {
        ASSERT_TRUE(actor->setDofs({0.3 * frame, -0.2 * frame, 0.5 * frame, 0.1 * frame}));
        runUpdate(*actor, frame);
        actor->getBound();
    }
    EXPECT_EQ(arm->count, 1);
}

TEST(BoundMode, AJointThatTranslatesKeepsABoundThatFollowsIt)
{
    // A slider (tx, rz) carrying an arm (rz) 1 along X, with a hand 1 further.
    ActorDefinitionBuilder b("slider");
    b.addJoint("carriage").dofs(Dof::TX | Dof::RZ);
    b.addJoint("arm", "carriage").offset(1, 0, 0).dofs(dofBit(Dof::RZ));
    b.addJoint("hand", "arm").offset(1, 0, 0);
    osg::ref_ptr<ActorNode> actor = makeCoveredActor(b);
    ASSERT_TRUE(actor.valid());
    EXPECT_FALSE(actor->getSkeletonNode(0u)->getBoundCoversRotations());
    EXPECT_TRUE(actor->getSkeletonNode(1u)->getBoundCoversRotations());
    CountingBound* carriage = countBounds(*actor->getSkeletonNode(0u));
    CountingBound* arm = countBounds(*actor->getSkeletonNode(1u));
    // The arm's ball: centre (1,0,0) in the carriage's frame, reach 1 + 0.1; the carriage carries it as it is.
    EXPECT_TRUE(sphereNear(actor->getBound(), osg::Vec3d(1, 0, 0), 1.1));
    ASSERT_TRUE(actor->setDof("carriage.tx", 3.0));
    ASSERT_TRUE(actor->setDof("arm.rz", 1.0));
    runUpdate(*actor, 1);
    EXPECT_TRUE(sphereNear(actor->getBound(), osg::Vec3d(4, 0, 0), 1.1)) << "the bound follows the slide";
    // Turned a quarter, the carriage slides along its own rotated X (the paper's translation after rotation).
    ASSERT_TRUE(actor->setDof("carriage.rz", osg::PI_2));
    runUpdate(*actor, 2);
    EXPECT_TRUE(sphereNear(actor->getBound(), osg::Vec3d(0, 4, 0), 1.1));
    EXPECT_EQ(carriage->count, 3);
    EXPECT_EQ(arm->count, 1) << "the arm only turned";
}

TEST(BoundMode, PicksHitTheHandWhereverItTurned)
{
    // Picking rejects subtrees by their bounds: a ball that did not hold the hand would lose the hit.
    osg::ref_ptr<ActorNode> actor = new ActorNode(makePlanarArm());
    actor->getSkeletonNode(3u)->addChild(makeBox(osg::Vec3(), 0.2f).get());
    actor->setBoundMode(ActorNode::BOUND_COVERS_ROTATIONS);
    actor->getBound();
    ASSERT_TRUE(actor->setDofs({osg::PI_2, 0.0, 0.0})); // the arm points along +Y: the hand at (0, 2.5, 0)
    runUpdate(*actor, 1);
    osg::ref_ptr<osgUtil::LineSegmentIntersector> ray =
        new osgUtil::LineSegmentIntersector(osg::Vec3d(0, 2.5, 5), osg::Vec3d(0, 2.5, -5));
    osgUtil::IntersectionVisitor visitor(ray.get());
    actor->accept(visitor);
    ASSERT_TRUE(ray->containsIntersections());
    const osg::Vec3d hit = ray->getFirstIntersection().getWorldIntersectPoint();
    EXPECT_TRUE(vec3Near(osg::Vec3d(hit.x(), hit.y(), std::abs(hit.z())), osg::Vec3d(0, 2.5, 0.1), 1e-6)) << hit;
}

TEST(BoundMode, ABallWidensWithAScaleAUserSets)
{
    osg::ref_ptr<ActorNode> actor = makeCoveredArm();
    SkeletonNode* lower = actor->getSkeletonNode(2u);
    lower->setMatrix(osg::Matrixd::scale(2, 2, 2) * osg::Matrixd::translate(1, 0, 0));
    EXPECT_TRUE(sphereNear(lower->getBound(), osg::Vec3d(1, 0, 0), 1.2));
}

TEST(BoundMode, ABallFollowsItsJointsCentreWhereverAMatrixSetByHandPutIt)
{
    osg::ref_ptr<ActorNode> actor = makeCoveredArm();
    SkeletonNode* lower = actor->getSkeletonNode(2u);
    lower->setMatrix(osg::Matrixd::translate(5, 0, 0)); // by hand: the actor's next write of this joint undoes it
    EXPECT_TRUE(sphereNear(lower->getBound(), osg::Vec3d(5, 0, 0), 0.6));
    // upper reaches 5 + 0.6 from its centre, which is 1 from base's: 6.6.
    EXPECT_TRUE(sphereNear(actor->getBound(), osg::Vec3d(0, 0, 0), 6.6));
    ASSERT_TRUE(actor->setDof("lower.rz", 0.5));
    runUpdate(*actor, 1);
    EXPECT_TRUE(sphereNear(lower->getBound(), osg::Vec3d(1, 0, 0), 0.6)) << "the centre moved back: a new ball";
    EXPECT_TRUE(sphereNear(actor->getBound(), osg::Vec3d(0, 0, 0), 2.6)) << "and new ones above it";
}

TEST(BoundMode, ANewDefinitionBoundToTheSameNodesMovesTheBallsCentre)
{
    osg::ref_ptr<ActorNode> actor = makeCoveredArm();
    // The same joints, lower now 2 along X from upper.
    ActorDefinitionBuilder b("longer arm");
    b.addJoint("base").dofs(dofBit(Dof::RZ));
    b.addJoint("upper", "base").offset(1, 0, 0).dofs(dofBit(Dof::RZ));
    b.addJoint("lower", "upper").offset(2, 0, 0).dofs(dofBit(Dof::RZ));
    b.addJoint("tip", "lower").offset(0.5, 0, 0);
    const BuildResult built = b.build();
    ASSERT_TRUE(built) << built.error;
    ASSERT_TRUE(actor->setDefinition(built.definition, ActorNode::BIND_EXISTING_SKELETON_NODES));
    runUpdate(*actor, 1);
    SkeletonNode* lower = actor->getSkeletonNode(2u);
    CountingBound* counter = countBounds(*lower);
    EXPECT_TRUE(sphereNear(lower->getBound(), osg::Vec3d(2, 0, 0), 0.6));
    // Turning it from now on keeps that ball: the node knows its new centre.
    for (unsigned frame = 2; frame <= 5; ++frame)
    {
        ASSERT_TRUE(actor->setDof("lower.rz", 0.2 * frame));
        runUpdate(*actor, frame);
        lower->getBound();
    }
    EXPECT_EQ(counter->count, 1);
}

TEST(BoundMode, CopiesKeepTheMode)
{
    osg::ref_ptr<ActorNode> actor = makeCoveredArm();
    osg::ref_ptr<ActorNode> copy = osg::clone(actor.get(), osg::CopyOp::SHALLOW_COPY);
    EXPECT_EQ(copy->getBoundMode(), ActorNode::BOUND_COVERS_ROTATIONS);
    EXPECT_TRUE(copy->getSkeletonNode(0u)->getBoundCoversRotations());
    EXPECT_TRUE(sphereNear(copy->getBound(), osg::Vec3d(0, 0, 0), 2.6));
}

TEST(BoundMode, AnActorFileSaysWhichAndSoDoesTheDocumentOfAnActor)
{
    std::istringstream text("osgactor 1\nactor arm {\n  bounds covers_rotations\n  joint base { dof rz }\n}\n");
    const ActorReadResult read = readActor(text, "arm.actor");
    ASSERT_TRUE(read) << read.error;
    EXPECT_TRUE(read.document.boundsCoverRotations);
    const ActorNodeResult made = createActorNode(read.document, read.definition, "arm.actor", nullptr);
    ASSERT_TRUE(made.actor.valid()) << made.error;
    EXPECT_EQ(made.actor->getBoundMode(), ActorNode::BOUND_COVERS_ROTATIONS);
    EXPECT_TRUE(made.actor->getSkeletonNode(0u)->getBoundCoversRotations());
    EXPECT_TRUE(extractActorDocument(*made.actor).boundsCoverRotations);
    made.actor->setBoundMode(ActorNode::BOUND_FOLLOWS_POSE);
    EXPECT_FALSE(extractActorDocument(*made.actor).boundsCoverRotations);

    // Without a bounds line, the default; follows_pose is the one a file must name.
    std::istringstream plain("osgactor 1\nactor arm {\n  joint base { dof rz }\n}\n");
    const ActorReadResult plainRead = readActor(plain, "plain.actor");
    ASSERT_TRUE(plainRead) << plainRead.error;
    EXPECT_TRUE(plainRead.document.boundsCoverRotations);
    std::istringstream follows("osgactor 1\nactor arm {\n  bounds follows_pose\n  joint base { dof rz }\n}\n");
    const ActorReadResult followsRead = readActor(follows, "follows.actor");
    ASSERT_TRUE(followsRead) << followsRead.error;
    const ActorNodeResult following = createActorNode(followsRead.document, followsRead.definition, "follows.actor",
                                                      nullptr);
    ASSERT_TRUE(following.actor.valid()) << following.error;
    EXPECT_EQ(following.actor->getBoundMode(), ActorNode::BOUND_FOLLOWS_POSE);
    EXPECT_FALSE(following.actor->getSkeletonNode(0u)->getBoundCoversRotations());
}

