#include "NodeTestUtil"

#include <osgActor/ActorGroup>
#include <osgActor/core/WorkerPool>

#include <atomic>
#include <numeric>

using namespace osgActor;
using namespace osgActor::test;

namespace {

/** Swings every DOF with time, with a per-actor phase, so each actor's pose is distinct and predictable. */
class SwingController : public Controller
{
public:
    explicit SwingController(double phase) : _phase(phase) {}
    void update(const ControllerContext& context, ControllerTarget& target) override
    {
        for (unsigned d = 0; d < target.pose.getNumDofs(); ++d)
            writeDof(target.pose, d, std::sin(context.time + _phase + d));
    }
    std::shared_ptr<Controller> cloneController() const override { return std::make_shared<SwingController>(*this); }

private:
    double _phase;
};

} // namespace

TEST(WorkerPool, RunsEveryItemExactlyOnce)
{
    for (unsigned threads : {1u, 2u, 4u})
    {
        WorkerPool pool(threads);
        EXPECT_EQ(pool.getNumThreads(), threads);
        for (unsigned count : {0u, 1u, 3u, 1000u})
        {
            std::vector<std::atomic<int>> hits(count);
            for (auto& h : hits) h = 0;
            pool.parallelFor(count, [&](unsigned i) { hits[i].fetch_add(1); });
            for (unsigned i = 0; i < count; ++i) ASSERT_EQ(hits[i].load(), 1) << threads << " threads, item " << i;
        }
    }
}

TEST(WorkerPool, RunsManyBatchesInARow)
{
    WorkerPool pool(3);
    std::atomic<long> sum{0};
    for (int batch = 0; batch < 500; ++batch) pool.parallelFor(37, [&](unsigned i) { sum += i; });
    EXPECT_EQ(sum.load(), 500L * (36 * 37 / 2));
}

TEST(ActorGroup, ParallelUpdateGivesTheSamePosesAsSerialUpdate)
{
    osg::ref_ptr<ActorGroup> parallel = new ActorGroup;
    parallel->setNumThreads(4);
    osg::ref_ptr<osg::Group> serial = new osg::Group;
    for (int a = 0; a < 50; ++a)
    {
        osg::ref_ptr<ActorNode> actor = new ActorNode(makePlanarArm());
        actor->addController(std::make_shared<SwingController>(0.1 * a));
        // Half of them write their nodes dirtying bounds (the covering default dirties none): that path runs on the
        // workers too.
        if (a % 2) actor->setBoundMode(ActorNode::BOUND_FOLLOWS_POSE);
        parallel->addChild(actor.get());
        serial->addChild(osg::clone(actor.get(), osg::CopyOp::SHALLOW_COPY));
    }
    for (unsigned frame = 1; frame <= 5; ++frame)
    {
        runUpdate(*parallel, frame);
        runUpdate(*serial, frame);
    }
    for (unsigned a = 0; a < 50; ++a)
    {
        ActorNode* p = static_cast<ActorNode*>(parallel->getChild(a));
        ActorNode* s = static_cast<ActorNode*>(serial->getChild(a));
        EXPECT_EQ(p->getNumUpdatesRun(), 5u) << "the group claims each frame once; the actor's callback skips";
        for (unsigned j = 0; j < p->getNumSkeletonNodes(); ++j)
            EXPECT_EQ(p->getSkeletonNode(j)->getMatrix(), s->getSkeletonNode(j)->getMatrix()) << a << " " << j;
    }
}

TEST(ActorGroup, LeavesBlockedActorsAndOtherChildrenAlone)
{
    osg::ref_ptr<ActorGroup> group = new ActorGroup;
    osg::ref_ptr<ActorNode> blocked = new ActorNode(makePlanarArm());
    blocked->addController(std::make_shared<SwingController>(0.0));
    blocked->setBlocked(true);
    group->addChild(blocked.get());
    group->addChild(makeBox(osg::Vec3(), 1.0f).get());
    runUpdate(*group, 1);
    EXPECT_EQ(blocked->getNumUpdatesRun(), 0u);
    EXPECT_TRUE(blocked->getSkeletonNode(0u)->getMatrix().isIdentity());
}

TEST(ActorGroup, BoundsFollowJointsMovedOnWorkerThreads)
{
    // Joint matrices are written on worker threads, which dirty only the actor's own nodes; the group's bound must
    // still see the move once the update thread has dirtied each actor.
    osg::ref_ptr<ActorGroup> group = new ActorGroup;
    group->setNumThreads(2);
    std::vector<ActorNode*> actors;
    for (int a = 0; a < 8; ++a)
    {
        osg::ref_ptr<ActorNode> actor = new ActorNode(makePlanarArm());
        actor->setBoundMode(ActorNode::BOUND_FOLLOWS_POSE); // so that a moved joint dirties bounds
        actor->getSkeletonNode("tip")->addChild(makeBox(osg::Vec3(), 0.1f).get());
        group->addChild(actor.get());
        actors.push_back(actor.get());
    }
    runUpdate(*group, 1);
    const osg::Vec3 raisedTip(0.0f, 2.5f, 0.0f);
    EXPECT_FALSE(group->getBound().contains(raisedTip)) << "every arm lies along +X";
    actors.back()->setDof("base.rz", osg::PI_2);
    runUpdate(*group, 2);
    EXPECT_TRUE(group->getBound().contains(raisedTip)) << "the last arm now points along +Y";
    // And back: a second move of the same joint, after the bounds were computed again.
    actors.back()->setDof("base.rz", 0.0);
    runUpdate(*group, 3);
    EXPECT_FALSE(group->getBound().contains(raisedTip));
}
