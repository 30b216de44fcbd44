// ActorGroup's cull prepared on its threads (issue 28): the render graph is the one the serial cull makes, leaf by
// leaf (drawables, model-view matrices to the bit, state graphs, bins, depths, order), whatever hangs below the joints,
// as actors move, stand still, leave the view or come back; below the group's threshold the cull is serial.
#include "CullProbe"
#include "NodeTestUtil"
#include "render/TestFigure.h"

#include <osgActor/ActorGroup>

#include <osg/BlendFunc>
#include <osg/LOD>
#include <osg/MatrixTransform>
#include <osg/Switch>

#include <gtest/gtest.h>

#include <random>

using namespace osgActor;
using namespace osgActor::test;

namespace {

/** Test figures on a grid under an ActorGroup of two threads, posed differently, the first few with every kind of
  * subtree the actor's cull hands to the ordinary traversal, a state set of their own or a transparent part. */
struct GroupCrowd
{
    osg::ref_ptr<ActorGroup> group = new ActorGroup;
    std::vector<osg::ref_ptr<ActorNode>> actors;

    explicit GroupCrowd(unsigned count)
    {
        group->setNumThreads(2);
        for (unsigned a = 0; a < count; ++a)
        {
            osg::ref_ptr<ActorNode> actor = makeTestFigure();
            actor->setPreTranslation(osg::Vec3d(1.1 * (a % 8), 1.5 * (a / 8), 0.0));
            actor->setDof("l_shoulder.ry", -0.2 * a);
            actor->setDof("r_knee.rx", 0.1 * a);
            actors.push_back(actor);
            group->addChild(actor.get());
        }
        actors[0]->getSkeletonNode("chest")->addChild(makeBox(osg::Vec3(0.0f, -0.1f, 0.1f), 0.1f));
        osg::ref_ptr<osg::Geode> glass = makeBox(osg::Vec3(0.0f, 0.1f, 0.0f), 0.08f);
        glass->getOrCreateStateSet()->setAttributeAndModes(new osg::BlendFunc);
        glass->getOrCreateStateSet()->setRenderingHint(osg::StateSet::TRANSPARENT_BIN);
        actors[1]->getSkeletonNode("head")->addChild(glass.get());
        osg::ref_ptr<osg::Switch> choice = new osg::Switch;
        choice->addChild(makeBox(osg::Vec3(), 0.05f), true);
        choice->addChild(makeBox(osg::Vec3(0.0f, 0.0f, 0.1f), 0.05f), false);
        actors[2]->getSkeletonNode("l_elbow")->addChild(choice.get());
        osg::ref_ptr<osg::LOD> lod = new osg::LOD;
        lod->addChild(makeBox(osg::Vec3(), 0.04f), 0.0f, 5.0f);
        lod->addChild(makeBox(osg::Vec3(), 0.08f), 5.0f, 1e6f);
        actors[3]->getSkeletonNode("l_knee")->addChild(lod.get());
        actors[4]->getOrCreateStateSet()->setMode(GL_LIGHTING, osg::StateAttribute::OFF);
        actors[5]->getSkeletonNode("r_hip")->setHidden(true);
        // A plain child of the group between the actors.
        group->insertChild(3, makeBox(osg::Vec3(0.0f, -1.0f, 0.5f), 0.2f));
        for (osg::ref_ptr<ActorNode>& actor : actors) actor->update(nullptr);
    }

    void setCullMode(ActorNode::CullMode mode)
    {
        for (osg::ref_ptr<ActorNode>& actor : actors) actor->setCullMode(mode);
    }
    /** Moves every actor a little, as a frame of animation would. */
    void pose(double t)
    {
        for (std::size_t a = 0; a < actors.size(); ++a)
        {
            actors[a]->setDof("l_elbow.rx", -0.5 - 0.3 * std::sin(t + a));
            actors[a]->setDof("pelvis.rz", 0.2 * std::cos(t + 0.5 * a));
            actors[a]->update(nullptr);
        }
    }
};

void expectSameLeaves(const std::vector<CulledLeaf>& leaves, const std::vector<CulledLeaf>& expected,
                      const char* what)
{
    ASSERT_EQ(leaves.size(), expected.size()) << what;
    for (std::size_t i = 0; i < expected.size(); ++i) EXPECT_TRUE(leaves[i] == expected[i]) << what << ", leaf " << i;
}

/** The leaves of a cull on the group's threads and of a serial one right after it. */
struct ParallelAndSerial
{
    std::vector<CulledLeaf> parallel;
    std::vector<CulledLeaf> serial;
};

/** Culls the crowd on the group's threads, then serially, at the next two frames (frame counts them), expecting the
  * parallel cull to have run and both to give the same near and far. */
ParallelAndSerial cullBothWays(GroupCrowd& crowd, CullProbe& probe, unsigned& frame)
{
    ParallelAndSerial culled;
    const unsigned before = crowd.group->getNumParallelCulls();
    culled.parallel = probe.cull(++frame);
    EXPECT_EQ(crowd.group->getNumParallelCulls(), before + 1);
    const double parallelNear = probe.calculatedNear(), parallelFar = probe.calculatedFar();
    const unsigned threshold = crowd.group->getMinActorsForParallelCull();
    crowd.group->setMinActorsForParallelCull(1000);
    culled.serial = probe.cull(++frame);
    crowd.group->setMinActorsForParallelCull(threshold);
    EXPECT_EQ(probe.calculatedNear(), parallelNear);
    EXPECT_EQ(probe.calculatedFar(), parallelFar);
    return culled;
}

} // namespace

TEST(ActorGroupCull, CullsSeriallyBelowItsThresholdOfActors)
{
    GroupCrowd crowd(6);
    EXPECT_GT(crowd.group->getMinActorsForParallelCull(), 6u); // the default pays off only above a few actors
    CullProbe probe(crowd.group.get());
    probe.lookAt(osg::Vec3d(4.0, -10.0, 2.0), osg::Vec3d(4.0, 0.0, 0.9));
    probe.cull(1);
    EXPECT_EQ(crowd.group->getNumParallelCulls(), 0u);
    crowd.group->setMinActorsForParallelCull(6);
    probe.cull(2);
    EXPECT_EQ(crowd.group->getNumParallelCulls(), 1u);
    crowd.group->setNumThreads(1); // nothing to share the work with
    probe.cull(3);
    EXPECT_EQ(crowd.group->getNumParallelCulls(), 1u);
}

TEST(ActorGroupCull, GivesTheSerialRenderGraphLeafByLeafFrameAfterFrame)
{
    for (const bool computeNearFar : {true, false})
    {
        SCOPED_TRACE(computeNearFar ? "near and far computed" : "near and far not computed");
        GroupCrowd crowd(24);
        crowd.group->setMinActorsForParallelCull(1);
        CullProbe probe(crowd.group.get());
        if (!computeNearFar) probe.sceneView().setComputeNearFarMode(osg::CullSettings::DO_NOT_COMPUTE_NEAR_FAR);
        // Views: all in view, close up on a few (the others cut or outside), from afar (small features culled).
        const osg::Vec3d eyes[] = {osg::Vec3d(4.0, -12.0, 2.0), osg::Vec3d(1.1, -1.6, 1.2), osg::Vec3d(4.0, -160.0, 1.0)};
        const osg::Vec3d centres[] = {osg::Vec3d(4.0, 1.5, 0.9), osg::Vec3d(1.1, 0.0, 1.0), osg::Vec3d(4.0, 0.0, 0.9)};
        unsigned frame = 0;
        for (unsigned view = 0; view < 3; ++view)
        {
            probe.lookAt(eyes[view], centres[view]);
            for (unsigned step = 0; step < 3; ++step)
            {
                SCOPED_TRACE("view " + std::to_string(view) + ", step " + std::to_string(step));
                // Moving, then standing still (the actors replay their last cull's calls).
                if (step < 2) crowd.pose(0.3 * frame);
                const ParallelAndSerial culled = cullBothWays(crowd, probe, frame);
                const std::vector<CulledLeaf>& parallel = culled.parallel;
                crowd.group->setMinActorsForParallelCull(1000);
                crowd.setCullMode(ActorNode::CULL_NODE_BY_NODE);
                const std::vector<CulledLeaf> ordinary = probe.cull(++frame);
                crowd.setCullMode(ActorNode::CULL_AS_ONE);
                crowd.group->setMinActorsForParallelCull(1);
                expectSameLeaves(parallel, culled.serial, "parallel against serial");
                // Without near and far computed, the cull as one leaves the frustum test of the drawables of an actor
                // in view to OpenGL (ActorNode::CULL_AS_ONE): close up, more of them reach the render graph.
                if (computeNearFar || view != 1) expectSameLeaves(parallel, ordinary, "parallel against node by node");
                if (view == 0)
                {
                    EXPECT_GT(parallel.size(), 24u * 14u); // the test can fail: the crowd is in view
                }
            }
        }
    }
}

TEST(ActorGroupCull, KeepsTheActorsOfAnotherCamerasCullOrdinary)
{
    // Two cameras culling the same group one inside the other's traversal (as OSG's cull threads may overlap): the
    // inner one finds the actors held by the outer one's preparation and culls them node by node, with the same
    // leaves.
    GroupCrowd crowd(10);
    crowd.group->setMinActorsForParallelCull(1);
    CullProbe inner(crowd.group.get());
    inner.lookAt(osg::Vec3d(4.0, -10.0, 2.0), osg::Vec3d(4.0, 1.0, 0.9));
    std::vector<CulledLeaf> innerLeaves;
    struct InnerCull : osg::NodeCallback
    {
        CullProbe* probe = nullptr;
        std::vector<CulledLeaf>* leaves = nullptr;
        bool done = false;
        void operator()(osg::Node* node, osg::NodeVisitor* nv) override
        {
            if (!done)
            {
                done = true;
                *leaves = probe->cull(7);
            }
            traverse(node, nv);
        }
    };
    osg::ref_ptr<InnerCull> callback = new InnerCull;
    callback->probe = &inner;
    callback->leaves = &innerLeaves;
    // Culled by the outer camera after the group prepared every actor: it hangs on the last actor's pelvis.
    crowd.actors.back()->getSkeletonNode("pelvis")->addCullCallback(callback.get());
    osg::ref_ptr<osg::Group> outerScene = new osg::Group;
    outerScene->addChild(crowd.group.get());
    CullProbe outer(outerScene.get());
    outer.lookAt(osg::Vec3d(4.0, -10.0, 2.0), osg::Vec3d(4.0, 1.0, 0.9));
    outer.cull(6);
    ASSERT_TRUE(callback->done);
    // The inner cull could not take the threads (the outer one held them) and culled serially.
    EXPECT_EQ(crowd.group->getNumParallelCulls(), 1u);
    crowd.actors.back()->getSkeletonNode("pelvis")->removeCullCallback(callback.get());
    crowd.setCullMode(ActorNode::CULL_NODE_BY_NODE);
    expectSameLeaves(innerLeaves, inner.cull(8), "inner cull against node by node");
}


TEST(ActorGroupCull, GivesTheSerialRenderGraphThroughEditsBetweenFrames)
{
    // Edits a user makes between frames, drawn at random (a fixed seed): poses, places, an actor's state set, cull
    // callback or mask, a joint's mask or hiding; the views and ways of computing near and far in turn. After each, the cull on the
    // group's threads (each actor's prepared calls made before the visitor enters it, where they can be) gives the
    // serial cull's render graph and near and far.
    GroupCrowd crowd(24);
    crowd.group->setMinActorsForParallelCull(1);
    CullProbe probe(crowd.group.get());
    // All in view, close up on a few near the group's origin and on a few far from it (where the actor's frame and
    // the group's differ most), from afar.
    const osg::Vec3d eyes[] = {osg::Vec3d(4.0, -12.0, 2.0), osg::Vec3d(1.1, -1.6, 1.2), osg::Vec3d(7.7, 2.9, 1.2),
                               osg::Vec3d(4.0, -160.0, 1.0)};
    const osg::Vec3d centres[] = {osg::Vec3d(4.0, 1.5, 0.9), osg::Vec3d(1.1, 0.0, 1.0), osg::Vec3d(7.7, 4.5, 1.0),
                                  osg::Vec3d(4.0, 0.0, 0.9)};
    const osg::CullSettings::ComputeNearFarMode modes[] = {osg::CullSettings::COMPUTE_NEAR_FAR_USING_BOUNDING_VOLUMES,
                                                           osg::CullSettings::DO_NOT_COMPUTE_NEAR_FAR,
                                                           osg::CullSettings::COMPUTE_NEAR_FAR_USING_PRIMITIVES};
    osg::ref_ptr<osg::StateSet> unlit = new osg::StateSet;
    unlit->setMode(GL_LIGHTING, osg::StateAttribute::OFF);
    osg::ref_ptr<osg::NodeCallback> passing = new osg::NodeCallback; // traverses, as a user's logging callback would
    const char* joints[] = {"l_elbow", "r_knee", "head", "chest", "pelvis"};
    std::mt19937 random(28);
    const auto pick = [&random](unsigned count) { return unsigned(random() % count); };
    unsigned frame = 0;
    std::size_t drawn = 0;
    for (unsigned step = 0; step < 60; ++step)
    {
        SCOPED_TRACE("step " + std::to_string(step));
        for (unsigned e = 0, edits = 1 + pick(3); e < edits; ++e)
        {
            ActorNode& actor = *crowd.actors[pick(unsigned(crowd.actors.size()))];
            switch (pick(6))
            {
            case 0: actor.setStateSet(actor.getStateSet() ? nullptr : unlit.get()); break;
            case 1:
                if (actor.getCullCallback()) actor.setCullCallback(nullptr);
                else actor.setCullCallback(passing.get());
                break;
            case 2: actor.setNodeMask(actor.getNodeMask() ? 0u : ~0u); break;
            case 3:
            {
                SkeletonNode& joint = *actor.getSkeletonNode(joints[pick(5)]);
                joint.setNodeMask(joint.getNodeMask() ? 0u : ~0u);
                break;
            }
            case 4:
            {
                SkeletonNode& joint = *actor.getSkeletonNode(joints[pick(5)]);
                joint.setHidden(!joint.getHidden());
                break;
            }
            default: actor.setPreTranslation(actor.getPreTranslation() + osg::Vec3d(0.0, 0.0, 0.25)); break;
            }
        }
        // Every view with every way of computing near and far, in turn.
        probe.lookAt(eyes[step % 4], centres[step % 4]);
        probe.sceneView().setComputeNearFarMode(modes[(step / 4) % 3]);
        if (pick(2)) crowd.pose(0.3 * step); // moving, or standing still
        const ParallelAndSerial culled = cullBothWays(crowd, probe, frame);
        expectSameLeaves(culled.parallel, culled.serial, "parallel against serial");
        drawn += culled.parallel.size();
    }
    EXPECT_GT(drawn, 60u * 24u * 4u); // the test can fail: much of the crowd is drawn at most steps
}
