// The instanced cull on the group's threads (InstancedActorGroup from getMinActorsForParallelCull() actors on, with
// more than one thread: osgActor/detail/InstancedCullParallel.cpp) must make the render graph, the texels, the near and
// far planes and the statistics of the cull on one thread, to the bit: two groups of the same crowd (clones of one
// figure, so the same parts), one culled on one thread and one on several, compared leaf by leaf and texel by texel,
// frame after frame, moving, still (instances kept), partly out of view, growing past the batches' regions, with other
// children and actors drawn ordinarily among them.
#include "CullProbe"
#include "InstancedCullComparison"
#include "render/TestFigure.h"

#include <osgActor/ActorNode>
#include <osgActor/InstancedActorGroup>

#include <osg/FrameStamp>
#include <osgUtil/UpdateVisitor>

#include <gtest/gtest.h>

#include <cstring>

#include <osg/MatrixTransform>
#include <osg/Switch>

#include <set>
#include <string>

using namespace osgActor;
using namespace osgActor::test;

namespace {

/** Two InstancedActorGroups of the same crowd, one culled on one thread and the other on several from 4 actors on,
  * each by a camera of its own, looking alike. */
struct TwinCrowds
{
    osg::ref_ptr<ActorNode> figure = makeTestFigure();
    osg::ref_ptr<InstancedActorGroup> serial = new InstancedActorGroup;
    osg::ref_ptr<InstancedActorGroup> parallel = new InstancedActorGroup;
    std::vector<osg::ref_ptr<ActorNode>> serialActors;
    std::vector<osg::ref_ptr<ActorNode>> parallelActors;
    CullProbe serialProbe{serial.get()};
    CullProbe parallelProbe{parallel.get()};
    unsigned frame = 0;

    explicit TwinCrowds(unsigned numActors, unsigned threads = 2)
    {
        serial->setNumThreads(1);
        parallel->setNumThreads(threads);
        for (InstancedActorGroup* group : {serial.get(), parallel.get()}) group->setMinActorsForParallelCull(4);
        for (unsigned a = 0; a < numActors; ++a) addActor(*figure);
        // The grid's left part in view: its right columns and far rows partly out.
        lookFrom(osg::Vec3d(1.5, -2.5, 1.6), osg::Vec3d(2.0, 3.0, 0.9));
    }
    /** An actor of the prototype's parts in each group, at the next place of a grid of rows of 8, posed apart. */
    void addActor(const ActorNode& prototype)
    {
        const unsigned a = static_cast<unsigned>(serialActors.size());
        for (InstancedActorGroup* group : {serial.get(), parallel.get()})
        {
            osg::ref_ptr<ActorNode> actor = osg::clone(&prototype, osg::CopyOp::SHALLOW_COPY);
            actor->setPreTranslation(osg::Vec3d(1.1 * (a % 8), 1.5 * (a / 8), 0.0));
            poseCrowdMember(*actor, a % 7);
            actor->update(nullptr);
            group->addChild(actor.get());
            (group == serial.get() ? serialActors : parallelActors).push_back(actor);
        }
    }
    /** The same change to both crowds: change(group, its actors). */
    template <class Change>
    void both(Change change)
    {
        change(*serial, serialActors);
        change(*parallel, parallelActors);
    }
    /** Every actor posed anew for the frame. */
    void move(int at)
    {
        both([at](InstancedActorGroup&, std::vector<osg::ref_ptr<ActorNode>>& actors) {
            for (std::size_t a = 0; a < actors.size(); ++a)
            {
                actors[a]->setDof("l_shoulder.ry", -0.25 * double(a % 5) - 0.1 * at);
                actors[a]->setDof("pelvis.rz", 0.05 * at + 0.1 * double(a % 9));
                actors[a]->update(nullptr);
            }
        });
    }
    void lookFrom(const osg::Vec3d& eye, const osg::Vec3d& centre)
    {
        serialProbe.lookAt(eye, centre);
        parallelProbe.lookAt(eye, centre);
    }
    void computeNearFar(osg::CullSettings::ComputeNearFarMode mode)
    {
        serialProbe.sceneView().setComputeNearFarMode(mode);
        parallelProbe.sceneView().setComputeNearFarMode(mode);
    }
    /** Culls both; whether the parallel one was culled on the threads (inParallel) or not, and the two alike. */
    ::testing::AssertionResult cullAlike(bool inParallel = true)
    {
        const unsigned before = parallel->getNumParallelCulls();
        ++frame;
        const std::vector<CulledLeaf> expected = withoutOwnStates(serialProbe, serialProbe.cull(frame));
        const std::vector<CulledLeaf> actual = withoutOwnStates(parallelProbe, parallelProbe.cull(frame));
        if ((parallel->getNumParallelCulls() == before + 1) != inParallel || serial->getNumParallelCulls() != 0)
            return ::testing::AssertionFailure() << "culled " << (inParallel ? "serially" : "in parallel");
        ::testing::AssertionResult same = sameInstancedCull(expected, actual);
        if (same) same = sameStatistics(*serial, *parallel);
        if (same) same = sameNearFar(serialProbe, parallelProbe);
        return same;
    }
    InstancedActorGroup::Statistics statistics() const { return parallel->getStatistics(); }
    /** Both groups' update traversals at the frame after the last cull's, as a viewer's next frame runs them. */
    void updateNextFrame()
    {
        osg::ref_ptr<osg::FrameStamp> stamp = new osg::FrameStamp;
        stamp->setFrameNumber(frame + 1);
        stamp->setSimulationTime((frame + 1) / 60.0);
        for (InstancedActorGroup* group : {serial.get(), parallel.get()})
        {
            osg::ref_ptr<osgUtil::UpdateVisitor> update = new osgUtil::UpdateVisitor;
            update->setFrameStamp(stamp.get());
            update->setTraversalNumber(frame + 1);
            group->accept(*update);
        }
    }
};

const osg::CullSettings::ComputeNearFarMode kNearFarModes[] = {
    osg::CullSettings::DO_NOT_COMPUTE_NEAR_FAR, osg::CullSettings::COMPUTE_NEAR_FAR_USING_BOUNDING_VOLUMES};

std::string nameOf(osg::CullSettings::ComputeNearFarMode mode)
{
    return mode == osg::CullSettings::DO_NOT_COMPUTE_NEAR_FAR ? "near and far not computed"
                                                              : "near and far from bounds";
}

} // namespace

TEST(InstancedParallelCull, AMovingCrowdPartlyInViewIsTheSerialCullFrameAfterFrame)
{
    for (const unsigned threads : {2u, 3u})
        for (const osg::CullSettings::ComputeNearFarMode mode : kNearFarModes)
        {
            TwinCrowds crowds(40, threads);
            crowds.computeNearFar(mode);
            for (int at = 0; at < 5; ++at)
            {
                crowds.move(at);
                EXPECT_TRUE(crowds.cullAlike()) << threads << " threads, " << nameOf(mode) << ", frame " << at;
                // The test can fail: actors in view and out of it, every one culled anew.
                EXPECT_GT(crowds.statistics().actorsInstanced, 10u);
                EXPECT_GT(crowds.statistics().actorsOutOfView, 4u);
                EXPECT_EQ(crowds.statistics().actorsKept, 0u);
            }
        }
}

TEST(InstancedParallelCull, AStillCrowdKeepsItsInstancesAsTheSerialCullDoesUntilTheCameraOrAPoseMoves)
{
    for (const osg::CullSettings::ComputeNearFarMode mode : kNearFarModes)
    {
        TwinCrowds crowds(24);
        crowds.computeNearFar(mode);
        for (int at = 0; at < 4; ++at) EXPECT_TRUE(crowds.cullAlike()) << nameOf(mode) << ", frame " << at;
        // The test can fail: the still actors in view add what they kept.
        const InstancedActorGroup::Statistics still = crowds.statistics();
        EXPECT_GT(still.actorsKept, 10u);
        EXPECT_EQ(still.actorsKept, still.actorsInstanced);
        crowds.lookFrom(osg::Vec3d(1.0, -6.0, 2.0), osg::Vec3d(3.0, 2.0, 0.9));
        for (int at = 0; at < 3; ++at) EXPECT_TRUE(crowds.cullAlike()) << nameOf(mode) << ", camera moved, " << at;
        crowds.both([](InstancedActorGroup&, std::vector<osg::ref_ptr<ActorNode>>& actors) {
            actors[3]->setDof("l_shoulder.ry", -1.5);
            actors[3]->update(nullptr);
        });
        for (int at = 0; at < 3; ++at) EXPECT_TRUE(crowds.cullAlike()) << nameOf(mode) << ", a pose moved, " << at;
        EXPECT_GT(crowds.statistics().actorsKept, 10u);
    }
}

TEST(InstancedParallelCull, OtherChildrenOrdinaryActorsAndAGrowingCrowdOfTwoKindsAreTheSerialCull)
{
    for (const osg::CullSettings::ComputeNearFarMode mode : kNearFarModes)
    {
        TwinCrowds crowds(16);
        crowds.computeNearFar(mode);
        // A floor among the actors (the same node in both), an actor culled node by node (drawn ordinarily), one
        // masked out.
        const osg::ref_ptr<osg::Geode> floor = makeFloor(20.0f);
        crowds.both([&floor](InstancedActorGroup& group, std::vector<osg::ref_ptr<ActorNode>>& actors) {
            group.insertChild(5, floor.get());
            actors[2]->setCullMode(ActorNode::CULL_NODE_BY_NODE);
            actors[9]->setNodeMask(0u);
        });
        EXPECT_TRUE(crowds.cullAlike()) << nameOf(mode);
        EXPECT_EQ(crowds.statistics().actorsOrdinary, 1u); // the test can fail
        // The crowd grows at every frame, past its batches' regions (each batch moved past them, as the serial cull
        // moves it), still and moving; then actors of another figure come (batches of their own, and verdicts made on
        // the cull thread).
        for (int at = 0; at < 4; ++at)
        {
            for (int k = 0; k < 3; ++k) crowds.addActor(*crowds.figure);
            if (at % 2) crowds.move(at);
            EXPECT_TRUE(crowds.cullAlike()) << nameOf(mode) << ", grown, frame " << at;
        }
        const osg::ref_ptr<ActorNode> other = makeTestFigure();
        for (int at = 0; at < 3; ++at)
        {
            crowds.addActor(*other);
            crowds.addActor(*crowds.figure);
            EXPECT_TRUE(crowds.cullAlike()) << nameOf(mode) << ", another figure, frame " << at;
        }
        EXPECT_GT(crowds.statistics().draws, 18u); // the test can fail: both figures' parts drawn
        // Then it shrinks: fewer instances than the regions hold.
        crowds.both([](InstancedActorGroup& group, std::vector<osg::ref_ptr<ActorNode>>&) {
            group.removeChildren(1, 12);
        });
        for (int at = 0; at < 2; ++at) EXPECT_TRUE(crowds.cullAlike()) << nameOf(mode) << ", shrunk, frame " << at;
    }
}

TEST(InstancedParallelCull, NodesBelowJointsAreTraversedInChildOrderAsTheSerialCullTraversesThem)
{
    // Props in some hands (a user's transform holding a part, one node for every hand it is in), a hidden arm, a
    // switch below a head: the actors stay instanced and the visitor traverses these on the cull thread, in child
    // order, as the serial cull does while it culls each actor.
    for (const osg::CullSettings::ComputeNearFarMode mode : kNearFarModes)
    {
        TwinCrowds crowds(16);
        crowds.computeNearFar(mode);
        osg::ref_ptr<osg::MatrixTransform> prop = new osg::MatrixTransform(osg::Matrix::translate(0.0, -0.1, -0.3));
        prop->addChild(makeSegment(0.5f, 0.03f, osg::Vec4(0.5f, 0.5f, 0.55f, 1.0f)));
        osg::ref_ptr<osg::Switch> switched = new osg::Switch;
        switched->addChild(makeJointBall(0.05f));
        crowds.both([&](InstancedActorGroup&, std::vector<osg::ref_ptr<ActorNode>>& actors) {
            for (std::size_t a = 0; a < actors.size(); a += 3)
                actors[a]->getSkeletonNode("r_elbow")->addChild(prop.get());
            actors[4]->getSkeletonNode("l_shoulder")->setHidden(true);
            actors[7]->getSkeletonNode("head")->addChild(switched.get());
        });
        for (int at = 0; at < 3; ++at)
        {
            if (at > 0) crowds.move(at);
            EXPECT_TRUE(crowds.cullAlike()) << nameOf(mode) << ", frame " << at;
        }
        EXPECT_EQ(crowds.statistics().actorsOrdinary, 0u);
        EXPECT_GT(crowds.statistics().actorsInstanced, 8u); // the test can fail: most of the crowd in view
        // Still: the instances and the subtrees' frames kept, the subtrees traversed again.
        for (int still = 0; still < 3; ++still) EXPECT_TRUE(crowds.cullAlike()) << nameOf(mode) << ", still " << still;
        EXPECT_EQ(crowds.statistics().actorsKept, crowds.statistics().actorsInstanced);
    }
}

TEST(InstancedParallelCull, ACrowdOverSeveralSmallBuffersIsTheSerialCull)
{
    TwinCrowds crowds(32);
    crowds.both([](InstancedActorGroup& group, std::vector<osg::ref_ptr<ActorNode>>&) {
        group.setMaxTexelsPerBuffer(64);
    });
    for (int at = 0; at < 4; ++at)
    {
        if (at % 2) crowds.move(at);
        EXPECT_TRUE(crowds.cullAlike()) << "frame " << at;
        EXPECT_GT(crowds.statistics().buffers, 2u); // the test can fail
    }
}

TEST(InstancedParallelCull, FewActorsOrAChildTwiceAreCulledSerially)
{
    {
        TwinCrowds crowds(3); // below the 4 actors from which the cull is parallel
        EXPECT_TRUE(crowds.cullAlike(false));
        crowds.addActor(*crowds.figure);
        EXPECT_TRUE(crowds.cullAlike(true));
    }
    {
        TwinCrowds crowds(8);
        crowds.both([](InstancedActorGroup& group, std::vector<osg::ref_ptr<ActorNode>>& actors) {
            group.addChild(actors[2].get());
        });
        EXPECT_TRUE(crowds.cullAlike(false));
        crowds.both([](InstancedActorGroup& group, std::vector<osg::ref_ptr<ActorNode>>&) {
            group.removeChildren(group.getNumChildren() - 1, 1);
        });
        EXPECT_TRUE(crowds.cullAlike(true));
    }
}

TEST(InstancedParallelCull, NearAndFarFromPrimitivesCullEachActorAsOneOnTheThreads)
{
    // The instanced cull does not follow each drawable's own frame that near and far from primitives clip in
    // (tests/nodes/test_instanced_replay.cpp): the group culls each actor as one, as an ActorGroup does, on its
    // threads from its threshold, with the serial render graph.
    TwinCrowds crowds(8);
    crowds.computeNearFar(osg::CullSettings::COMPUTE_NEAR_FAR_USING_PRIMITIVES);
    const unsigned before = crowds.parallel->getNumParallelCulls();
    ++crowds.frame;
    const std::vector<CulledLeaf> expected = crowds.serialProbe.cull(crowds.frame);
    const std::vector<CulledLeaf> actual = crowds.parallelProbe.cull(crowds.frame);
    EXPECT_EQ(crowds.parallel->getNumParallelCulls(), before + 1);
    EXPECT_GT(expected.size(), 8u); // the test can fail: the actors' parts are drawn
    ASSERT_EQ(actual.size(), expected.size());
    // Two crowds alike, not the same nodes: each leaf at the same place, depth and bin.
    for (std::size_t i = 0; i < expected.size(); ++i)
    {
        EXPECT_EQ(std::memcmp(actual[i].modelView, expected[i].modelView, sizeof expected[i].modelView), 0)
            << "leaf " << i;
        EXPECT_EQ(actual[i].depth, expected[i].depth) << "leaf " << i;
        EXPECT_EQ(actual[i].bin, expected[i].bin) << "leaf " << i;
    }
    EXPECT_TRUE(sameNearFar(crowds.serialProbe, crowds.parallelProbe));
    EXPECT_EQ(crowds.statistics().actorsInstanced, 0u);
}

TEST(InstancedParallelCull, TheUpdatePolicyNotesTheViewsThatSeeEachActorAsTheSerialCullDoes)
{
    // Actors updated only when seen, at half or quarter rate where small on screen: the views that saw each actor,
    // and its size, noted on the cull thread in child order from what the threads found, decide its next updates as
    // the serial cull's notes do.
    TwinCrowds crowds(40);
    ActorNode::UpdatePolicy policy;
    policy.onlyWhenSeen = true;
    policy.halfRateBelowPixels = 300.0f;
    policy.quarterRateBelowPixels = 150.0f;
    crowds.both([&policy](InstancedActorGroup&, std::vector<osg::ref_ptr<ActorNode>>& actors) {
        for (const osg::ref_ptr<ActorNode>& actor : actors) actor->setUpdatePolicy(policy);
    });
    for (int at = 0; at < 6; ++at)
    {
        crowds.updateNextFrame();
        EXPECT_TRUE(crowds.cullAlike()) << "frame " << at;
    }
    crowds.updateNextFrame();
    std::set<unsigned> skips;
    for (std::size_t a = 0; a < crowds.serialActors.size(); ++a)
    {
        EXPECT_EQ(crowds.parallelActors[a]->getNumUpdatesSkipped(), crowds.serialActors[a]->getNumUpdatesSkipped())
            << "actor " << a;
        skips.insert(crowds.serialActors[a]->getNumUpdatesSkipped());
    }
    // The test can fail: actors updated at every frame, at a lower rate, and never (out of view).
    EXPECT_GE(skips.size(), 3u);
}
