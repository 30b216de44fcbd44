// With near and far computed from bounding volumes (osgViewer's default), the instanced cull (InstancedActorGroup,
// osgActor/detail/InstancedCull.h) adds a moving actor's parts from its plan's compiled list, near and far from each
// part's box in the same loop, where every top joint's sphere lies wholly inside the frustum (no box is tested below
// it), and follows the plan's steps, box by box, where one does not. Both must give the same: the same instances in the
// same order and texels, and the same near and far, to the bit. Compared, frame after frame of a moving crowd, on one
// thread and on the group's threads: the crowd culled moving (the compiled list where it may) against its twin culled
// a second time unchanged (the cull that records an idle actor's instances goes through the steps), leaf by leaf and
// texel by texel; and against the ordinary traversal (its parts and near and far), with the crowd wholly in view,
// partly cut by the frustum, and the eye among the actors (parts behind it, with and without frustum culling).
#include "CullProbe"
#include "InstancedCullComparison"
#include "render/TestFigure.h"

#include <osgActor/ActorNode>
#include <osgActor/InstancedActorGroup>
#include <osgActor/detail/InstancedCull.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <iomanip>
#include <set>
#include <string>
#include <utility>

using namespace osgActor;
using namespace osgActor::test;

namespace {

/** An InstancedActorGroup whose last cull's count of actors added from their plans' compiled lists can be read. */
class CompiledCountingGroup : public InstancedActorGroup
{
public:
    unsigned actorsCompiled() const { return _cullState->getStatistics().actorsCompiled; }
};

/** The test figure with a marker, one geode below four joints: one batch of four instances an actor, which the
  * compiled list and the steps must add in the plan's order. */
osg::ref_ptr<ActorNode> makeMarkedFigure()
{
    osg::ref_ptr<ActorNode> figure = makeTestFigure();
    const osg::ref_ptr<osg::Geode> marker = makeJointBall(0.05f);
    for (const char* joint : {"r_knee", "head", "l_elbow", "pelvis"})
        figure->getSkeletonNode(joint)->addChild(marker.get());
    return figure;
}

constexpr unsigned kPartsPerFigure = 18 + 4;

/** Two instanced groups of the same crowd (clones of one marked figure, in a grid of rows of 8) and a plain group of the
  * first's actors culled node by node, each seen by a camera of its own, looking alike, near and far computed from
  * bounding volumes; culled on one thread or, from 4 actors on, on threads. */
struct Crowds
{
    osg::ref_ptr<ActorNode> figure = makeMarkedFigure();
    osg::ref_ptr<CompiledCountingGroup> moving = new CompiledCountingGroup;
    osg::ref_ptr<CompiledCountingGroup> still = new CompiledCountingGroup;
    osg::ref_ptr<osg::Group> plain = new osg::Group;
    std::vector<osg::ref_ptr<ActorNode>> movingActors;
    std::vector<osg::ref_ptr<ActorNode>> stillActors;
    CullProbe movingProbe{moving.get()};
    CullProbe stillProbe{still.get()};
    CullProbe ordinaryProbe{plain.get()};
    unsigned frame = 0;
    unsigned threads;

    Crowds(unsigned numActors, unsigned numThreads) : threads(numThreads)
    {
        for (CompiledCountingGroup* group : {moving.get(), still.get()})
        {
            group->setNumThreads(threads);
            group->setMinActorsForParallelCull(4);
        }
        for (unsigned a = 0; a < numActors; ++a)
            for (CompiledCountingGroup* group : {moving.get(), still.get()})
            {
                osg::ref_ptr<ActorNode> actor = osg::clone(figure.get(), osg::CopyOp::SHALLOW_COPY);
                actor->setPreTranslation(osg::Vec3d(1.1 * (a % 8), 1.5 * (a / 8), 0.0));
                group->addChild(actor.get());
                if (group == moving.get()) plain->addChild(actor.get());
                (group == moving.get() ? movingActors : stillActors).push_back(actor);
            }
        for (CullProbe* probe : {&movingProbe, &stillProbe, &ordinaryProbe})
            probe->sceneView().setComputeNearFarMode(osg::CullSettings::COMPUTE_NEAR_FAR_USING_BOUNDING_VOLUMES);
    }
    void lookFrom(const osg::Vec3d& eye, const osg::Vec3d& centre)
    {
        for (CullProbe* probe : {&movingProbe, &stillProbe, &ordinaryProbe}) probe->lookAt(eye, centre);
    }
    /** Frustum culling off (no plane at all), for every camera; OSG's default culls by the frustum's sides. */
    void cullNoFrustum()
    {
        for (CullProbe* probe : {&movingProbe, &stillProbe, &ordinaryProbe})
        {
            osgUtil::SceneView& view = probe->sceneView();
            view.setCullingMode(view.getCullingMode() & ~osg::CullSettings::VIEW_FRUSTUM_CULLING);
        }
    }
    /** Both crowds posed for frame at, every actor apart, and updated. */
    void pose(int at)
    {
        for (std::vector<osg::ref_ptr<ActorNode>>* actors : {&movingActors, &stillActors})
            for (std::size_t a = 0; a < actors->size(); ++a)
            {
                ActorNode& actor = *(*actors)[a];
                poseCrowdMember(actor, unsigned(a % 7));
                actor.setDof("l_shoulder.ry", -0.25 * double(a % 5) - 0.1 * at);
                actor.setDof("pelvis.rz", 0.05 * at + 0.1 * double(a % 9));
                actor.update(nullptr);
            }
    }
    /** Culls the crowds at the pose of the last update: each group twice, so that the second cull's batches have
      * regions as large as its instances. The moving crowd's bounds are recomputed between (as a moving actor's are at
      * every frame): culled afresh, by the compiled list where it may. The still crowd's actors did not change: their
      * instances are recorded, through the plan's steps. Whether the two second culls are the same (render graph,
      * texels, near and far, statistics), on the threads where asked, and the moving crowd's parts and near and far
      * the ordinary traversal's. */
    ::testing::AssertionResult cullAlike()
    {
        const unsigned before = moving->getNumParallelCulls() + still->getNumParallelCulls();
        ++frame;
        movingProbe.cull(frame);
        for (const osg::ref_ptr<ActorNode>& actor : movingActors) actor->dirtyBound();
        const std::vector<CulledLeaf> compiled = withoutOwnStates(movingProbe, movingProbe.cull(frame));
        stillProbe.cull(frame);
        const std::vector<CulledLeaf> steps = withoutOwnStates(stillProbe, stillProbe.cull(frame));
        const unsigned parallelCulls = moving->getNumParallelCulls() + still->getNumParallelCulls() - before;
        if (parallelCulls != (threads > 1 ? 4u : 0u))
            return ::testing::AssertionFailure() << parallelCulls << " culls of 4 on the threads";
        if (still->actorsCompiled() != 0u)
            return ::testing::AssertionFailure() << still->actorsCompiled() << " recorded actors from the compiled list";
        ::testing::AssertionResult same = sameInstancedCull(steps, compiled);
        if (same) same = sameStatistics(*still, *moving);
        if (same) same = sameNearFar(stillProbe, movingProbe);
        if (!same) return same;

        for (const osg::ref_ptr<ActorNode>& actor : movingActors) actor->setCullMode(ActorNode::CULL_NODE_BY_NODE);
        ordinary = ordinaryInstancesOf(ordinaryProbe.cull(frame));
        for (const osg::ref_ptr<ActorNode>& actor : movingActors) actor->setCullMode(ActorNode::CULL_AS_ONE);
        if (instancesOf(compiled) != ordinary)
            return ::testing::AssertionFailure() << "not the ordinary traversal's " << ordinary.size() << " parts";
        return sameNearFar(ordinaryProbe, movingProbe);
    }
    /** The ordinary traversal's parts at the last cullAlike(). */
    std::vector<Instance> ordinary;
};

std::string threadsNamed(unsigned threads) { return threads > 1 ? "on threads" : "on one thread"; }

} // namespace

TEST(InstancedNearFar, ACrowdWhollyInViewIsAddedFromTheCompiledListsAsTheStepsAddIt)
{
    // Every top joint's sphere wholly inside the frustum: every actor from its compiled list.
    for (const unsigned threads : {1u, 2u})
    {
        Crowds crowds(16, threads);
        crowds.lookFrom(osg::Vec3d(3.85, -12.0, 3.0), osg::Vec3d(3.85, 0.75, 0.9));
        for (int at = 0; at < 4; ++at)
        {
            crowds.pose(at);
            EXPECT_TRUE(crowds.cullAlike()) << threadsNamed(threads) << ", frame " << at;
            EXPECT_EQ(crowds.ordinary.size(), 16u * kPartsPerFigure) << "frame " << at; // every part seen
            EXPECT_EQ(crowds.moving->getStatistics().actorsInstanced, 16u);
            EXPECT_EQ(crowds.moving->actorsCompiled(), 16u) << threadsNamed(threads) << ", frame " << at;
        }
    }
}

TEST(InstancedNearFar, ACrowdPartlyCutByTheFrustumIsTheStepsCullWhereATopSphereIsNotWhollyInside)
{
    // The grid's left part in view: actors wholly inside (the compiled list), actors across the frustum's sides (the
    // steps: their parts' boxes tested), actors out of view.
    for (const unsigned threads : {1u, 2u})
    {
        Crowds crowds(40, threads);
        crowds.lookFrom(osg::Vec3d(1.5, -2.5, 1.6), osg::Vec3d(2.0, 3.0, 0.9));
        std::set<std::size_t> counts;
        for (int at = 0; at < 4; ++at)
        {
            crowds.pose(at);
            EXPECT_TRUE(crowds.cullAlike()) << threadsNamed(threads) << ", frame " << at;
            const InstancedActorGroup::Statistics statistics = crowds.moving->getStatistics();
            // The test can fail: some actors from the compiled list, some by the steps, some out of view.
            EXPECT_GT(crowds.moving->actorsCompiled(), 2u) << threadsNamed(threads) << ", frame " << at;
            EXPECT_LT(crowds.moving->actorsCompiled() + 2u, statistics.actorsInstanced) << "frame " << at;
            EXPECT_GT(statistics.actorsOutOfView, 4u);
            counts.insert(crowds.ordinary.size());
        }
        // Parts of the actors across the sides culled: not a whole number of figures.
        for (const std::size_t count : counts) EXPECT_NE(count % kPartsPerFigure, 0u) << threadsNamed(threads);
    }
}

TEST(InstancedNearFar, AnEyeAmongTheActorsGivesTheStepsPartsAndNearAndFarWithOrWithoutFrustumCulling)
{
    // The eye walks through the grid's first rows, looking along its depth: parts in front, parts behind the eye,
    // parts across its plane (a near distance below zero). With frustum culling, the actors around the eye are culled
    // by the steps; without it, every actor comes from its compiled list, whose parts wholly behind the eye are dropped
    // (the visitor drops them) and give no near and far.
    for (const unsigned threads : {1u, 2u})
        for (const bool frustumCulling : {true, false})
        {
            Crowds crowds(24, threads);
            if (!frustumCulling) crowds.cullNoFrustum();
            const std::string what = threadsNamed(threads) + (frustumCulling ? ", frustum culling" : ", no frustum");
            bool acrossEyePlane = false, partsBehind = false;
            unsigned compiled = 0;
            int at = 0;
            for (double y = -2.0; y < 2.5; y += 0.3, ++at)
            {
                crowds.pose(at);
                const osg::Vec3d eye(2.2, y, 1.1);
                crowds.lookFrom(eye, eye + osg::Vec3d(0.2, 7.0, -0.3));
                EXPECT_TRUE(crowds.cullAlike()) << what << ", eye at y " << y;
                acrossEyePlane = acrossEyePlane || crowds.ordinaryProbe.calculatedNear() < 0.0;
                const InstancedActorGroup::Statistics statistics = crowds.moving->getStatistics();
                if (!frustumCulling)
                {
                    EXPECT_EQ(statistics.actorsInstanced, 24u) << what << ", eye at y " << y;
                    EXPECT_EQ(crowds.moving->actorsCompiled(), 24u) << what << ", eye at y " << y;
                    partsBehind = partsBehind || crowds.ordinary.size() < 24u * kPartsPerFigure;
                }
                compiled += crowds.moving->actorsCompiled();
            }
            EXPECT_TRUE(acrossEyePlane) << what; // the test can fail: a part crossed the eye plane on the way
            EXPECT_GT(compiled, 0u) << what;
            if (!frustumCulling)
            {
                EXPECT_TRUE(partsBehind) << what; // parts were dropped behind the eye
            }
        }
}
