// The actor culled as one (ActorNode::CULL_AS_ONE, issue 28) gives the render graph the ordinary traversal gives:
// the same drawables with the same model-view matrices (to the bit), state graphs, bins and order, whatever hangs
// below the joints; hidden joints, cull callbacks, user nodes, picking and other visitors keep working.
#include "CullProbe"
#include "NodeTestUtil"
#include "render/TestFigure.h"

#include <osgActor/ActorNode>

#include <osg/BlendFunc>
#include <osg/LOD>
#include <osg/MatrixTransform>
#include <osg/ShapeDrawable>
#include <osg/Switch>
#include <osgUtil/CullVisitor>
#include <osgUtil/IntersectionVisitor>
#include <osgUtil/LineSegmentIntersector>

#include <gtest/gtest.h>

#include <cstring>

using namespace osgActor;
using namespace osgActor::test;

namespace {

/** Counts cull-traversal visits and records what the visitor holds there. */
class CullRecorder : public osg::NodeCallback
{
public:
    void operator()(osg::Node* node, osg::NodeVisitor* nv) override
    {
        osgUtil::CullVisitor* cv = nv->asCullVisitor();
        if (cv)
        {
            ++visits;
            std::memcpy(modelView, cv->getModelViewMatrix()->ptr(), sizeof modelView);
            matricesPushed = cv->getModelViewStack().size();
            nodePath = cv->getNodePath();
        }
        traverse(node, nv);
    }
    unsigned visits = 0;
    double modelView[16] = {};
    std::size_t matricesPushed = 0;
    osg::NodePath nodePath;
};

/** Test figures in a row along X, each posed a little differently, with every kind of subtree the fast cull must
  * hand to the ordinary traversal hanging somewhere below their joints. */
struct Crowd
{
    osg::ref_ptr<osg::Group> scene = new osg::Group;
    std::vector<osg::ref_ptr<ActorNode>> actors;
    osg::ref_ptr<CullRecorder> recorder = new CullRecorder;
    osg::ref_ptr<osg::Geode> hiddenPart;

    explicit Crowd(unsigned count)
    {
        for (unsigned a = 0; a < count; ++a)
        {
            osg::ref_ptr<ActorNode> actor = makeTestFigure();
            actor->setPreTranslation(osg::Vec3d(1.1 * a, 0.3 * (a % 3), 0.0));
            actor->setDof("l_shoulder.ry", -0.2 * a);
            actor->setDof("r_knee.rx", 0.1 * a);
            actors.push_back(actor);
            scene->addChild(actor.get());
        }
        ActorNode& first = *actors.front();
        // Plain geometry without any state, on the chest and right on the actor node.
        first.getSkeletonNode("chest")->addChild(makeBox(osg::Vec3(0.0f, -0.1f, 0.1f), 0.1f));
        first.addChild(makeBox(osg::Vec3(0.3f, 0.0f, 0.0f), 0.05f));
        // A state set on a skeleton node and one on a drawable.
        first.getSkeletonNode("l_knee")->getOrCreateStateSet()->setMode(GL_LIGHTING, osg::StateAttribute::OFF);
        osg::ref_ptr<osg::Geode> withDrawableState = makeBox(osg::Vec3(0.0f, 0.0f, -0.2f), 0.06f);
        withDrawableState->getDrawable(0)->getOrCreateStateSet()->setMode(GL_CULL_FACE, osg::StateAttribute::ON);
        first.getSkeletonNode("r_elbow")->addChild(withDrawableState.get());
        // A transparent part: a depth-sorted bin, where the depth of each leaf counts.
        osg::ref_ptr<osg::Geode> glass = makeBox(osg::Vec3(0.0f, 0.1f, 0.0f), 0.08f);
        glass->getOrCreateStateSet()->setAttributeAndModes(new osg::BlendFunc);
        glass->getOrCreateStateSet()->setRenderingHint(osg::StateSet::TRANSPARENT_BIN);
        first.getSkeletonNode("head")->addChild(glass.get());
        // User nodes below joints: a switch (one child off), an LOD, a transform of the user's.
        osg::ref_ptr<osg::Switch> choice = new osg::Switch;
        choice->addChild(makeBox(osg::Vec3(), 0.05f), true);
        choice->addChild(makeBox(osg::Vec3(0.0f, 0.0f, 0.1f), 0.05f), false);
        first.getSkeletonNode("l_elbow")->addChild(choice.get());
        osg::ref_ptr<osg::LOD> lod = new osg::LOD;
        lod->addChild(makeBox(osg::Vec3(), 0.04f), 0.0f, 5.0f);
        lod->addChild(makeBox(osg::Vec3(), 0.08f), 5.0f, 1e6f);
        first.getSkeletonNode("l_knee")->addChild(lod.get());
        osg::ref_ptr<osg::MatrixTransform> sword = new osg::MatrixTransform(osg::Matrix::translate(0.0, 0.0, -0.3));
        sword->addChild(makeBox(osg::Vec3(), 0.05f));
        first.getSkeletonNode("r_elbow")->addChild(sword.get());
        // A geode with a cull callback, three joints deep (pelvis, chest, l_shoulder).
        osg::ref_ptr<osg::Geode> watched = makeBox(osg::Vec3(0.0f, 0.0f, -0.1f), 0.05f);
        watched->setCullCallback(recorder.get());
        first.getSkeletonNode("l_shoulder")->addChild(watched.get());
        // A hidden joint with its own geometry.
        hiddenPart = makeBox(osg::Vec3(), 0.2f);
        first.getSkeletonNode("r_hip")->addChild(hiddenPart.get());
        first.getSkeletonNode("r_hip")->setHidden(true);
        for (osg::ref_ptr<ActorNode>& actor : actors) actor->update(nullptr);
    }

    void setCullMode(ActorNode::CullMode mode)
    {
        for (osg::ref_ptr<ActorNode>& actor : actors) actor->setCullMode(mode);
    }
};

bool containsDrawable(const std::vector<CulledLeaf>& leaves, const osg::Drawable* drawable)
{
    for (const CulledLeaf& leaf : leaves)
        if (leaf.drawable == drawable) return true;
    return false;
}

/** Culls a crowd of the given size with both modes from one camera, compares the render graphs leaf by leaf and
  * returns how many leaves they have. */
std::size_t expectSameRenderGraph(unsigned numActors, const osg::Vec3d& eye, const osg::Vec3d& centre,
                                  bool computeNearFar = true)
{
    Crowd crowd(numActors);
    CullProbe probe(crowd.scene.get());
    if (!computeNearFar) probe.sceneView().setComputeNearFarMode(osg::CullSettings::DO_NOT_COMPUTE_NEAR_FAR);
    probe.lookAt(eye, centre);
    crowd.setCullMode(ActorNode::CULL_NODE_BY_NODE);
    const std::vector<CulledLeaf> ordinary = probe.cull(1);
    const double ordinaryNear = probe.calculatedNear(), ordinaryFar = probe.calculatedFar();
    crowd.setCullMode(ActorNode::CULL_AS_ONE);
    const std::vector<CulledLeaf> asOne = probe.cull(2);
    // The planes come from each drawable's box corners nearest and farthest along the view in its joint's frame.
    EXPECT_EQ(probe.calculatedNear(), ordinaryNear);
    EXPECT_EQ(probe.calculatedFar(), ordinaryFar);
    EXPECT_EQ(asOne.size(), ordinary.size());
    for (std::size_t i = 0; i < ordinary.size() && i < asOne.size(); ++i)
        EXPECT_TRUE(asOne[i] == ordinary[i]) << "leaf " << i;
    // The test can fail: the actors' drawables went into batches (the ordinary traversal makes none).
    std::size_t numBatched = 0;
    for (const CulledLeaf& leaf : asOne) numBatched += leaf.batched;
    EXPECT_GT(numBatched, ordinary.size() / 2);
    return ordinary.size();
}

} // namespace

TEST(CullAsOne, IsTheDefault)
{
    osg::ref_ptr<ActorNode> actor = makeTestFigure();
    EXPECT_EQ(actor->getCullMode(), ActorNode::CULL_AS_ONE);
    actor->setCullMode(ActorNode::CULL_NODE_BY_NODE);
    osg::ref_ptr<ActorNode> copy = osg::clone(actor.get(), osg::CopyOp::SHALLOW_COPY);
    EXPECT_EQ(copy->getCullMode(), ActorNode::CULL_NODE_BY_NODE);
}

TEST(CullAsOne, GivesTheOrdinaryRenderGraphWithEveryKindOfSubtree)
{
    const std::size_t numLeaves = expectSameRenderGraph(6, osg::Vec3d(2.5, -6.0, 1.5), osg::Vec3d(2.5, 0.0, 0.9));
    // Six figures of 18 parts each, the first one's 8 visible additions (the switch's second child and the LOD's
    // near child are off), less the hidden hip's two parts and its knee's two.
    EXPECT_EQ(numLeaves, 6u * 18u + 8u - 4u);
}

TEST(CullAsOne, GivesTheOrdinaryRenderGraphWhenActorsAreHalfOutOfView)
{
    // Close up on the second figure: the first and third are cut by the frustum's sides, the others outside. The
    // near and far planes are computed from the drawables, so those outside the frustum must not count.
    const std::size_t numLeaves = expectSameRenderGraph(6, osg::Vec3d(1.1, -1.6, 1.2), osg::Vec3d(1.1, 0.0, 1.0));
    EXPECT_GT(numLeaves, 5u);
    EXPECT_LT(numLeaves, 6u * 18u); // the test can fail: parts were culled
}

TEST(CullAsOne, CullsSmallFeaturesAsTheOrdinaryTraversalDoes)
{
    // From afar the balls on the joints are under OSG's two pixels and culled; the bodies are not.
    const std::size_t numLeaves =
        expectSameRenderGraph(6, osg::Vec3d(2.5, -160.0, 1.0), osg::Vec3d(2.5, 0.0, 0.9));
    EXPECT_GT(numLeaves, 0u);
    EXPECT_LT(numLeaves, 6u * 18u);
}

TEST(CullAsOne, GivesTheOrdinaryRenderGraphWithoutNearFarComputation)
{
    const std::size_t numLeaves =
        expectSameRenderGraph(3, osg::Vec3d(1.1, -6.0, 1.5), osg::Vec3d(1.1, 0.0, 0.9), false);
    EXPECT_EQ(numLeaves, 3u * 18u + 8u - 4u);
}

TEST(CullAsOne, HiddenJointsAreNotDrawnInEitherMode)
{
    Crowd crowd(1);
    CullProbe probe(crowd.scene.get());
    probe.lookAt(osg::Vec3d(0.0, -6.0, 1.0), osg::Vec3d(0.0, 0.0, 0.9));
    EXPECT_FALSE(containsDrawable(probe.cull(1), crowd.hiddenPart->getDrawable(0)));
    crowd.actors[0]->getSkeletonNode("r_hip")->setHidden(false);
    EXPECT_TRUE(containsDrawable(probe.cull(2), crowd.hiddenPart->getDrawable(0)));
}

TEST(CullAsOne, CullCallbacksBelowJointsSeeTheSameMatrixAndPathWithOneMatrixPushedForAllJoints)
{
    Crowd crowd(1);
    CullProbe probe(crowd.scene.get());
    probe.lookAt(osg::Vec3d(0.0, -6.0, 1.0), osg::Vec3d(0.0, 0.0, 0.9));
    crowd.setCullMode(ActorNode::CULL_NODE_BY_NODE);
    probe.cull(1);
    ASSERT_EQ(crowd.recorder->visits, 1u);
    double ordinaryModelView[16];
    std::memcpy(ordinaryModelView, crowd.recorder->modelView, sizeof ordinaryModelView);
    const osg::NodePath ordinaryPath = crowd.recorder->nodePath;
    const std::size_t ordinaryPushed = crowd.recorder->matricesPushed;

    crowd.setCullMode(ActorNode::CULL_AS_ONE);
    probe.cull(2);
    ASSERT_EQ(crowd.recorder->visits, 2u);
    EXPECT_EQ(std::memcmp(crowd.recorder->modelView, ordinaryModelView, sizeof ordinaryModelView), 0);
    EXPECT_EQ(crowd.recorder->nodePath, ordinaryPath);
    // The ordinary traversal pushed a model-view matrix (and a culling set with it) at pelvis, chest and
    // l_shoulder; the actor as one only the one for l_shoulder, where the callback's subtree needs it.
    EXPECT_EQ(crowd.recorder->matricesPushed + 2u, ordinaryPushed);
}

TEST(CullAsOne, LeavesPickingAndOtherVisitorsAlone)
{
    Crowd crowd(1);
    ActorNode& actor = *crowd.actors[0];
    // A segment down through the head: it hits the head's sphere (and the glass box on it).
    const osg::Vec3d head = actor.getJointWorldPosition(unsigned(actor.getJointIndex("head")));
    osg::ref_ptr<osgUtil::LineSegmentIntersector> picker =
        new osgUtil::LineSegmentIntersector(head + osg::Vec3d(0.0, 0.0, 1.0), head + osg::Vec3d(0.0, 0.0, 0.05));
    osgUtil::IntersectionVisitor pick(picker.get());
    crowd.scene->accept(pick);
    ASSERT_TRUE(picker->containsIntersections());
    bool throughHead = false;
    for (const osg::Node* node : picker->getFirstIntersection().nodePath)
        throughHead = throughHead || node == actor.getSkeletonNode("head");
    EXPECT_TRUE(throughHead);
    // A hidden joint is not picked.
    const osg::Vec3d hip = actor.getJointWorldPosition(unsigned(actor.getJointIndex("r_hip")));
    osg::ref_ptr<osgUtil::LineSegmentIntersector> hipPicker =
        new osgUtil::LineSegmentIntersector(hip + osg::Vec3d(0.0, -1.0, 0.0), hip + osg::Vec3d(0.0, 1.0, 0.0));
    osgUtil::IntersectionVisitor hipPick(hipPicker.get());
    crowd.scene->accept(hipPick);
    for (const osgUtil::LineSegmentIntersector::Intersection& hit : hipPicker->getIntersections())
        EXPECT_NE(hit.drawable.get(), crowd.hiddenPart->getDrawable(0));

    // A node visitor still goes through every skeleton node.
    struct Counter : osg::NodeVisitor
    {
        Counter() : osg::NodeVisitor(TRAVERSE_ALL_CHILDREN) {}
        void apply(osg::Transform& transform) override
        {
            if (dynamic_cast<SkeletonNode*>(&transform)) ++joints;
            traverse(transform);
        }
        unsigned joints = 0;
    } counter;
    crowd.scene->accept(counter);
    EXPECT_EQ(counter.joints, actor.getNumSkeletonNodes());
}

TEST(CullAsOne, ComputesTheOrdinaryNearAndFarPlanesWhateverWayTheJointsFace)
{
    // The visitor takes each box's nearest and farthest corners along the view in the frame the box is drawn in:
    // joints turned half round (pelvis about Z, arms about all three axes) face other ways than the actor.
    osg::ref_ptr<osg::Group> scene = new osg::Group;
    osg::ref_ptr<ActorNode> actor = makeTestFigure();
    actor->setDof("pelvis.rz", 2.8);
    actor->setDof("l_shoulder.rx", 2.2);
    actor->setDof("l_shoulder.ry", -2.9);
    actor->setDof("r_shoulder.rz", 3.0);
    actor->setDof("l_elbow.rx", -2.4);
    actor->getSkeletonNode("l_elbow")->addChild(makeBox(osg::Vec3(0.05f, -0.02f, -0.2f), 0.07f));
    actor->update(nullptr);
    scene->addChild(actor.get());
    CullProbe probe(scene.get());
    for (const osg::Vec3d& eye : {osg::Vec3d(0.7, -1.2, 1.6), osg::Vec3d(-1.1, 0.9, 0.4), osg::Vec3d(0.2, 1.5, 2.4)})
    {
        probe.lookAt(eye, osg::Vec3d(0.0, 0.0, 1.0));
        actor->setCullMode(ActorNode::CULL_NODE_BY_NODE);
        const std::vector<CulledLeaf> ordinary = probe.cull(1);
        const double ordinaryNear = probe.calculatedNear(), ordinaryFar = probe.calculatedFar();
        actor->setCullMode(ActorNode::CULL_AS_ONE);
        const std::vector<CulledLeaf> asOne = probe.cull(2);
        EXPECT_EQ(probe.calculatedNear(), ordinaryNear) << "eye " << eye.x() << " " << eye.y() << " " << eye.z();
        EXPECT_EQ(probe.calculatedFar(), ordinaryFar) << "eye " << eye.x() << " " << eye.y() << " " << eye.z();
        EXPECT_EQ(asOne.size(), ordinary.size());
    }
}
