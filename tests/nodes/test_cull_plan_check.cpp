// The cull plan's check (osgActor/detail/ActorCullPlan.h): OSG changes a node's mask, state set, cull callback,
// culling flags and a transform's reference frame through setters that tell nobody, so the plan compares them at
// every cull. A joint's are compared as one block of osg::Node's bytes against the few distinct blocks the plan
// keeps; each setter, on any joint, must make the plan no longer current, and setting a value back must make it
// current again.
#include <osgActor/detail/ActorCullPlan.h>

#include <osgActor/core/ActorDefinitionBuilder>

#include "render/TestFigure.h"

#include <osg/NodeCallback>
#include <osg/StateSet>

#include <gtest/gtest.h>

#include <functional>
#include <string>
#include <vector>

using namespace osgActor;
using namespace osgActor::test;
using detail::ActorCullPlan;

namespace {

/** A plan of the test figure, and whether an edit of one joint makes it stale and undoing it current again. */
struct PlanCheck
{
    osg::ref_ptr<ActorNode> actor = makeTestFigure();
    osg::ref_ptr<ActorCullPlan> plan = new ActorCullPlan(*actor);

    void expectSeen(const std::string& joint, const std::function<void(SkeletonNode&)>& edit,
                    const std::function<void(SkeletonNode&)>& undo)
    {
        SkeletonNode& node = *actor->getSkeletonNode(joint);
        ASSERT_TRUE(plan->isCurrent()) << joint;
        edit(node);
        EXPECT_FALSE(plan->isCurrent()) << joint;
        undo(node);
        EXPECT_TRUE(plan->isCurrent()) << joint;
    }
};

} // namespace

TEST(CullPlanCheck, AnUneditedActorsPlanStaysCurrent)
{
    PlanCheck check;
    EXPECT_TRUE(check.plan->isCurrent());
    EXPECT_TRUE(check.plan->isCurrent());
}

TEST(CullPlanCheck, ANodeMaskSetOnAnyJointIsSeen)
{
    PlanCheck check;
    for (const char* joint : {"pelvis", "l_shoulder", "head", "r_knee"})
        check.expectSeen(
            joint, [](SkeletonNode& node) { node.setNodeMask(0x1); },
            [](SkeletonNode& node) { node.setNodeMask(~0u); });
}

TEST(CullPlanCheck, AStateSetOrCullCallbackSetOnAJointIsSeen)
{
    PlanCheck check;
    osg::ref_ptr<osg::StateSet> state = new osg::StateSet;
    check.expectSeen(
        "l_elbow", [&](SkeletonNode& node) { node.setStateSet(state.get()); },
        [](SkeletonNode& node) { node.setStateSet(nullptr); });
    osg::ref_ptr<osg::NodeCallback> callback = new osg::NodeCallback;
    check.expectSeen(
        "r_hip", [&](SkeletonNode& node) { node.setCullCallback(callback.get()); },
        [](SkeletonNode& node) { node.setCullCallback(nullptr); });
}

TEST(CullPlanCheck, CullingTurnedOffOnAJointOrBelowItIsSeen)
{
    PlanCheck check;
    check.expectSeen(
        "l_knee", [](SkeletonNode& node) { node.setCullingActive(false); },
        [](SkeletonNode& node) { node.setCullingActive(true); });
    // A child with culling off counts on its parent joint (osg::Node::_numChildrenWithCullingDisabled).
    osg::ref_ptr<osg::Group> child = new osg::Group;
    child->setCullingActive(false);
    SkeletonNode& elbow = *check.actor->getSkeletonNode("l_elbow");
    ASSERT_TRUE(elbow.addChild(child.get()));
    check.plan = new ActorCullPlan(*check.actor);
    check.expectSeen(
        "l_elbow", [&](SkeletonNode&) { child->setCullingActive(true); },
        [&](SkeletonNode&) { child->setCullingActive(false); });
}

TEST(CullPlanCheck, AReferenceFrameChangedOnAJointIsSeenEvenWithItsCullingFlagSetBack)
{
    PlanCheck check;
    check.expectSeen(
        "r_elbow", [](SkeletonNode& node) { node.setReferenceFrame(osg::Transform::ABSOLUTE_RF); },
        [](SkeletonNode& node) { node.setReferenceFrame(osg::Transform::RELATIVE_RF); });
    // setReferenceFrame() turns culling off with an absolute frame: turned back on by hand, the joint's flags are
    // those planned again, and only its frame differs.
    check.expectSeen(
        "head",
        [](SkeletonNode& node) {
            node.setReferenceFrame(osg::Transform::ABSOLUTE_RF_INHERIT_VIEWPOINT);
            node.setCullingActive(true);
        },
        [](SkeletonNode& node) { node.setReferenceFrame(osg::Transform::RELATIVE_RF); });
}

TEST(CullPlanCheck, JointsWithAStateSetEachAreEachComparedWithTheirOwn)
{
    // As many distinct blocks as joints: each joint's check must still be against its own state set.
    PlanCheck check;
    std::vector<osg::ref_ptr<osg::StateSet>> states;
    for (unsigned i = 0; i < check.actor->getNumSkeletonNodes(); ++i)
    {
        states.push_back(new osg::StateSet);
        check.actor->getSkeletonNode(i)->setStateSet(states.back().get());
    }
    check.plan = new ActorCullPlan(*check.actor);
    ASSERT_TRUE(check.plan->isCurrent());
    SkeletonNode& first = *check.actor->getSkeletonNode(1u);
    SkeletonNode& last = *check.actor->getSkeletonNode(check.actor->getNumSkeletonNodes() - 1);
    osg::ref_ptr<osg::StateSet> firstState = first.getStateSet();
    first.setStateSet(last.getStateSet());
    EXPECT_FALSE(check.plan->isCurrent());
    first.setStateSet(firstState.get());
    EXPECT_TRUE(check.plan->isCurrent());
}

TEST(CullPlanCheck, MoreDistinctJointsThanAByteCountsAreEachComparedWithTheirOwn)
{
    // The plan numbers a joint's distinct flags in a byte while there are at most 256 of them, in four bytes past
    // that: a chain of 300 joints with a state set each takes the wider numbers.
    ActorDefinitionBuilder builder("chain");
    builder.addJoint("j0");
    for (unsigned i = 1; i < 300; ++i)
        builder.addJoint("j" + std::to_string(i), "j" + std::to_string(i - 1)).offset(0, 0, 1);
    const BuildResult built = builder.build();
    ASSERT_TRUE(built) << built.error;
    osg::ref_ptr<ActorNode> actor = new ActorNode(built.definition);
    ASSERT_EQ(actor->getNumSkeletonNodes(), 300u);
    std::vector<osg::ref_ptr<osg::StateSet>> states;
    for (unsigned i = 0; i < actor->getNumSkeletonNodes(); ++i)
    {
        states.push_back(new osg::StateSet);
        actor->getSkeletonNode(i)->setStateSet(states.back().get());
    }
    osg::ref_ptr<ActorCullPlan> plan = new ActorCullPlan(*actor);
    ASSERT_TRUE(plan->isCurrent());
    for (unsigned joint : {0u, 255u, 256u, 299u})
    {
        SkeletonNode& node = *actor->getSkeletonNode(joint);
        // Another joint's state set (one the plan knows, under another number), then its own back.
        node.setStateSet(states[joint == 0 ? 299 : joint - 1].get());
        EXPECT_FALSE(plan->isCurrent()) << joint;
        node.setStateSet(states[joint].get());
        EXPECT_TRUE(plan->isCurrent()) << joint;
        node.setNodeMask(0x2);
        EXPECT_FALSE(plan->isCurrent()) << joint;
        node.setNodeMask(~0u);
        EXPECT_TRUE(plan->isCurrent()) << joint;
    }
}
