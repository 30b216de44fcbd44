// A joint of a crowd's actor edited in place through OSG's setters, which tell nobody (its node mask, state set, cull
// callback, culling flag, reference frame), must change the very next cull of an InstancedActorGroup, culled on one
// thread and on two. Its actors keep their cull plans from cull to cull and check them at each
// (osgActor/detail/ActorCullPlan.h: isCurrent() compares every joint's flags at once, against the one block all the
// joints had or against each joint's own). Before a still camera an unchanged actor's instances are kept
// (InstancedActorGroup::Statistics::actorsKept): an edit seen makes a new plan, so that the actor is culled afresh at
// that cull, and setting the value back does too; an edit not seen would leave it kept. Each of those culls draws the
// ordinary traversal's parts.
#include "CullProbe"
#include "InstancedCullComparison"
#include "render/TestFigure.h"

#include <osgActor/ActorNode>
#include <osgActor/InstancedActorGroup>
#include <osgActor/detail/InstancedDraw.h>

#include <osg/NodeCallback>
#include <osg/StateSet>

#include <gtest/gtest.h>

#include <algorithm>
#include <functional>
#include <string>
#include <vector>

using namespace osgActor;
using namespace osgActor::test;

namespace {

/** Six test figures posed apart under an instanced group culled on `threads` threads and, the same nodes, under a
  * plain group culled node by node; their joints' node masks maskA, or maskA and maskB in turn (two distinct
  * blocks of flags an actor). Near and far not computed. */
struct EditedCrowd
{
    osg::ref_ptr<InstancedActorGroup> instanced = new InstancedActorGroup;
    osg::ref_ptr<osg::Group> plain = new osg::Group;
    std::vector<osg::ref_ptr<ActorNode>> actors;
    CullProbe instancedProbe{instanced.get()};
    CullProbe ordinaryProbe{plain.get()};
    unsigned threads;
    unsigned frame = 0;

    EditedCrowd(unsigned numThreads, osg::Node::NodeMask maskA, osg::Node::NodeMask maskB) : threads(numThreads)
    {
        actors = addPosedRow(*plain, 6);
        for (const osg::ref_ptr<ActorNode>& actor : actors)
        {
            for (unsigned j = 0; j < actor->getNumSkeletonNodes(); ++j)
                actor->getSkeletonNode(j)->setNodeMask(j % 2 ? maskB : maskA);
            instanced->addChild(actor.get());
        }
        instanced->setNumThreads(threads);
        instanced->setMinActorsForParallelCull(4);
        for (CullProbe* probe : {&instancedProbe, &ordinaryProbe})
        {
            probe->sceneView().setComputeNearFarMode(osg::CullSettings::DO_NOT_COMPUTE_NEAR_FAR);
            probe->lookAt(osg::Vec3d(2.75, -9.0, 1.2), osg::Vec3d(2.75, 0.0, 0.9));
        }
    }
    /** The parts the instanced cull draws: its instances, and the leaves of the actors it draws ordinarily. */
    std::vector<Instance> cullInstanced()
    {
        const unsigned before = instanced->getNumParallelCulls();
        const std::vector<CulledLeaf> leaves = instancedProbe.cull(++frame);
        EXPECT_EQ(instanced->getNumParallelCulls(), before + (threads > 1 ? 1u : 0u)) << "culled on other threads";
        std::vector<CulledLeaf> ordinaryLeaves;
        for (const CulledLeaf& leaf : leaves)
            if (!dynamic_cast<const detail::InstancedDraw*>(leaf.drawable)) ordinaryLeaves.push_back(leaf);
        std::vector<Instance> parts = instancesOf(leaves);
        const std::vector<Instance> ordinary = ordinaryInstancesOf(ordinaryLeaves);
        parts.insert(parts.end(), ordinary.begin(), ordinary.end());
        std::sort(parts.begin(), parts.end());
        return parts;
    }
    std::vector<Instance> cullOrdinarily()
    {
        for (const osg::ref_ptr<ActorNode>& actor : actors) actor->setCullMode(ActorNode::CULL_NODE_BY_NODE);
        std::vector<Instance> parts = ordinaryInstancesOf(ordinaryProbe.cull(++frame));
        for (const osg::ref_ptr<ActorNode>& actor : actors) actor->setCullMode(ActorNode::CULL_AS_ONE);
        return parts;
    }
    unsigned kept() const { return instanced->getStatistics().actorsKept; }

    /** Culls until every actor's instances are kept, then edits the joint, culls once, undoes the edit, culls once:
      * each of those two culls must draw the ordinary traversal's parts and not keep actor a's instances (it is
      * culled afresh, or ordinarily where the edit handed the joint to the ordinary traversal). */
    void expectSeen(unsigned a, const std::string& joint, const std::function<void(SkeletonNode&)>& edit,
                    const std::function<void(SkeletonNode&)>& undo, const std::string& what)
    {
        const std::string where = what + ", actor " + std::to_string(a) + ", " + joint + ", " +
                                  std::to_string(threads) + " thread(s)";
        SkeletonNode& node = *actors[a]->getSkeletonNode(joint);
        for (int settle = 0; settle < 3; ++settle) cullInstanced();
        ASSERT_EQ(kept(), actors.size()) << where << ": the test can fail, every actor kept";
        edit(node);
        std::vector<Instance> parts = cullInstanced();
        EXPECT_EQ(kept(), actors.size() - 1) << where << ": the edit not seen";
        EXPECT_EQ(parts, cullOrdinarily()) << where << ": edited";
        undo(node);
        parts = cullInstanced();
        EXPECT_EQ(kept(), actors.size() - 1) << where << ": the undoing not seen";
        EXPECT_EQ(parts, cullOrdinarily()) << where << ": undone";
        // And back on the actor's own path: its joint taken by a plan again, its instances kept by the still culls.
        for (int settle = 0; settle < 3; ++settle) parts = cullInstanced();
        EXPECT_EQ(kept(), actors.size()) << where << ": not kept again after the undoing";
        EXPECT_EQ(instanced->getStatistics().actorsOrdinary, 0u) << where << ": still culled ordinarily";
        EXPECT_EQ(parts, cullOrdinarily()) << where << ": settled";
    }
};

/** Each edit, on the first actor's first joint, a middle one's and the last one's last (the look-ahead of the cull
  * asks for each actor's nodes while culling the one before), each in a crowd of its own: a joint given a cull
  * callback or an absolute frame is handed to the ordinary traversal (the plan does not look into such a subtree)
  * but still watched, so that after the undoing its actor is instanced and kept again. */
void expectEveryEditSeen(unsigned threads, osg::Node::NodeMask maskA, osg::Node::NodeMask maskB)
{
    typedef std::function<void(SkeletonNode&)> Edit;
    osg::ref_ptr<osg::StateSet> state = new osg::StateSet;
    osg::ref_ptr<osg::NodeCallback> callback = new osg::NodeCallback;
    const struct
    {
        unsigned actor;
        const char* joint;
    } places[] = {{0, "pelvis"}, {3, "l_elbow"}, {5, "r_knee"}};
    for (const auto& place : places)
    {
        const osg::Node::NodeMask mask = EditedCrowd(1, maskA, maskB)
                                             .actors[place.actor]
                                             ->getSkeletonNode(place.joint)
                                             ->getNodeMask();
        const Edit maskBack = [mask](SkeletonNode& node) { node.setNodeMask(mask); };
        const struct
        {
            const char* what;
            Edit edit, undo;
        } edits[] = {
            // Bits cleared (only a bitwise AND of the joints' blocks shows it), bits set (only an OR does).
            {"a node mask cleared", [](SkeletonNode& node) { node.setNodeMask(0); }, maskBack},
            {"a node mask's bit set", [mask](SkeletonNode& node) { node.setNodeMask(mask | 0x10000u); }, maskBack},
            {"a state set", [&](SkeletonNode& node) { node.setStateSet(state.get()); },
             [](SkeletonNode& node) { node.setStateSet(nullptr); }},
            {"a cull callback", [&](SkeletonNode& node) { node.setCullCallback(callback.get()); },
             [](SkeletonNode& node) { node.setCullCallback(nullptr); }},
            {"culling turned off", [](SkeletonNode& node) { node.setCullingActive(false); },
             [](SkeletonNode& node) { node.setCullingActive(true); }},
            // setReferenceFrame() turns culling off with an absolute frame: set back on, only the frame differs.
            {"an absolute reference frame",
             [](SkeletonNode& node) {
                 node.setReferenceFrame(osg::Transform::ABSOLUTE_RF);
                 node.setCullingActive(true);
             },
             [](SkeletonNode& node) { node.setReferenceFrame(osg::Transform::RELATIVE_RF); }},
        };
        for (const auto& edit : edits)
            EditedCrowd(threads, maskA, maskB).expectSeen(place.actor, place.joint, edit.edit, edit.undo, edit.what);
    }
}

} // namespace

TEST(InstancedJointEdits, EachEditOfAJointOfActorsWhoseJointsAreAlikeIsSeenAtTheNextCullOnOneThread)
{
    expectEveryEditSeen(1, 0xffffu, 0xffffu);
}

TEST(InstancedJointEdits, EachEditOfAJointOfActorsWhoseJointsAreAlikeIsSeenAtTheNextCullOnTwoThreads)
{
    expectEveryEditSeen(2, 0xffffu, 0xffffu);
}

TEST(InstancedJointEdits, EachEditOfAJointOfActorsWithTwoKindsOfJointsIsSeenAtTheNextCullOnOneThread)
{
    expectEveryEditSeen(1, 0xffffu, 0xfff7u);
}

TEST(InstancedJointEdits, EachEditOfAJointOfActorsWithTwoKindsOfJointsIsSeenAtTheNextCullOnTwoThreads)
{
    expectEveryEditSeen(2, 0xffffu, 0xfff7u);
}
