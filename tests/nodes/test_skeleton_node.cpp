#include "NodeTestUtil"

#include <osg/Geode>
#include <osgUtil/IntersectionVisitor>
#include <osgUtil/LineSegmentIntersector>

using namespace osgActor;
using namespace osgActor::test;

namespace {

/** Counts the geodes a traversal of the given visitor type reaches. */
class GeodeCounter : public osg::NodeVisitor
{
public:
    explicit GeodeCounter(osg::NodeVisitor::VisitorType type)
        : osg::NodeVisitor(type, osg::NodeVisitor::TRAVERSE_ALL_CHILDREN)
    {
    }
    void apply(osg::Geode&) override { ++count; }
    unsigned count = 0;
};

unsigned geodesReachedBy(osg::Node& root, osg::NodeVisitor::VisitorType type)
{
    GeodeCounter counter(type);
    root.accept(counter);
    return counter.count;
}

/** Whether a segment along -Z through (x, y) hits anything below root. */
bool picks(osg::Node& root, double x, double y)
{
    osg::ref_ptr<osgUtil::LineSegmentIntersector> segment =
        new osgUtil::LineSegmentIntersector(osg::Vec3d(x, y, 10), osg::Vec3d(x, y, -10));
    osgUtil::IntersectionVisitor visitor(segment.get());
    root.accept(visitor);
    return segment->containsIntersections();
}

} // namespace

TEST(SkeletonNode, HiddenSubtreeIsNotCulled)
{
    osg::ref_ptr<ActorNode> actor = new ActorNode(makePlanarArm());
    actor->getSkeletonNode("upper")->addChild(makeBox(osg::Vec3(0.5f, 0, 0), 0.2f).get());
    actor->getSkeletonNode("tip")->addChild(makeBox(osg::Vec3(), 0.2f).get());
    EXPECT_EQ(geodesReachedBy(*actor, osg::NodeVisitor::CULL_VISITOR), 2u);
    actor->getSkeletonNode("lower")->setHidden(true);
    EXPECT_EQ(geodesReachedBy(*actor, osg::NodeVisitor::CULL_VISITOR), 1u) << "the tip, below lower, is hidden";
    EXPECT_EQ(geodesReachedBy(*actor, osg::NodeVisitor::NODE_VISITOR), 2u) << "other traversals still see it";
    actor->getSkeletonNode("lower")->setHidden(false);
    EXPECT_EQ(geodesReachedBy(*actor, osg::NodeVisitor::CULL_VISITOR), 2u);
}

TEST(SkeletonNode, HiddenSubtreeCannotBePicked)
{
    osg::ref_ptr<ActorNode> actor = new ActorNode(makePlanarArm());
    actor->getSkeletonNode("tip")->addChild(makeBox(osg::Vec3(), 0.2f).get());
    EXPECT_TRUE(picks(*actor, 2.5, 0.0));
    actor->getSkeletonNode("tip")->setHidden(true);
    EXPECT_FALSE(picks(*actor, 2.5, 0.0));
}

TEST(SkeletonNode, HiddenPartsStayPosed)
{
    osg::ref_ptr<ActorNode> actor = new ActorNode(makePlanarArm());
    actor->getSkeletonNode("tip")->addChild(makeBox(osg::Vec3(), 0.2f).get());
    actor->getSkeletonNode("upper")->setHidden(true);
    actor->setDof("base.rz", osg::PI_2);
    runUpdate(*actor, 1);
    EXPECT_TRUE(vec3Near(actor->getJointWorldPosition(3), osg::Vec3d(0, 2.5, 0), 1e-14));
    EXPECT_TRUE(vec3Near(actor->getSkeletonNode("tip")->getWorldMatrices().front().getTrans(),
                         osg::Vec3d(0, 2.5, 0), 1e-14));
    // Shown again, it appears where the body now is.
    actor->getSkeletonNode("upper")->setHidden(false);
    EXPECT_TRUE(picks(*actor, 0.0, 2.5));
    EXPECT_FALSE(picks(*actor, 2.5, 0.0));
}

TEST(SkeletonNode, CopyKeepsJointIndexNameAndHideFlag)
{
    osg::ref_ptr<SkeletonNode> node = new SkeletonNode(3, "l_knee");
    node->setHidden(true);
    osg::ref_ptr<SkeletonNode> copy = osg::clone(node.get(), osg::CopyOp::SHALLOW_COPY);
    EXPECT_EQ(copy->getJointIndex(), 3u);
    EXPECT_EQ(copy->getName(), "l_knee");
    EXPECT_TRUE(copy->getHidden());
    EXPECT_EQ(copy->getDataVariance(), osg::Object::DYNAMIC);
    EXPECT_STREQ(copy->libraryName(), "osgActor");
    EXPECT_STREQ(copy->className(), "SkeletonNode");
}
