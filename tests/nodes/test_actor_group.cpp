#include "NodeTestUtil"

#include <osgActor/ActorGroup>
#include <osgActor/core/detail/WorkerPool>

#include <atomic>
#include <chrono>
#include <numeric>
#include <thread>

using namespace osgActor;
using namespace osgActor::test;

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

TEST(WorkerPool, TellsEachItemTheThreadThatRunsItOneThreadAtATime)
{
    // Each thread's index below getNumThreads(), the caller's 0, and no two items at once under one index (each
    // item marks its index busy while it runs): working space per thread is safe.
    for (unsigned threads : {1u, 2u, 4u})
    {
        WorkerPool pool(threads);
        for (unsigned count : {0u, 3u, 1000u})
        {
            std::vector<std::atomic<int>> hits(count);
            for (auto& h : hits) h = 0;
            std::vector<std::atomic<bool>> busy(threads);
            for (auto& b : busy) b = false;
            std::atomic<bool> clash{false}, outOfRange{false};
            pool.parallelForWithThread(count, [&](unsigned i, unsigned thread) {
                hits[i].fetch_add(1);
                if (thread >= threads)
                {
                    outOfRange = true;
                    return;
                }
                if (busy[thread].exchange(true)) clash = true;
                std::this_thread::yield();
                busy[thread] = false;
            });
            EXPECT_FALSE(outOfRange.load()) << threads << " threads";
            EXPECT_FALSE(clash.load()) << threads << " threads";
            for (unsigned i = 0; i < count; ++i) ASSERT_EQ(hits[i].load(), 1) << threads << " threads, item " << i;
        }
    }
}

TEST(WorkerPool, FinishesTheSliceOfAThreadThatIsStillBusy)
{
    // Two threads, four items, one at a time: the caller's slice is items 0-1, the worker's 2-3. Whichever thread
    // runs item 2 waits there for item 3, which only the other thread can then run: it must take it from a slice
    // that is not its own (were slices not shared, item 2 would wait out its deadline and the test fail).
    WorkerPool pool(2);
    std::atomic<bool> item3Ran{false};
    std::atomic<bool> item2TimedOut{false};
    std::vector<std::atomic<int>> hits(4);
    for (auto& h : hits) h = 0;
    pool.parallelFor(4, [&](unsigned i) {
        hits[i].fetch_add(1);
        if (i == 3) item3Ran = true;
        if (i != 2) return;
        const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
        while (!item3Ran)
        {
            if (std::chrono::steady_clock::now() > deadline) { item2TimedOut = true; return; }
            std::this_thread::yield();
        }
    }, 1);
    EXPECT_FALSE(item2TimedOut.load());
    for (unsigned i = 0; i < 4; ++i) EXPECT_EQ(hits[i].load(), 1) << "item " << i;
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

namespace {

/** Counts its calls and passes the traversal on. */
class CountingCallback : public osg::NodeCallback
{
public:
    void operator()(osg::Node* node, osg::NodeVisitor* nv) override
    {
        ++calls;
        traverse(node, nv);
    }
    int calls = 0;
};

osg::ref_ptr<ActorNode> makeSwingingArm(double phase)
{
    osg::ref_ptr<ActorNode> actor = new ActorNode(makePlanarArm());
    actor->addController(std::make_shared<SwingController>(phase));
    return actor;
}

} // namespace

TEST(ActorGroup, StillRunsUserCallbacksOnAndBelowItsActors)
{
    // The group skips visiting actors with nothing more to run than their own update: these have more.
    osg::ref_ptr<ActorGroup> group = new ActorGroup;
    group->setNumThreads(2);
    osg::ref_ptr<ActorNode> nested = makeSwingingArm(0.0);
    osg::ref_ptr<CountingCallback> onActor = new CountingCallback;
    nested->addUpdateCallback(onActor.get()); // nested behind the actor's own ActorUpdateCallback
    osg::ref_ptr<ActorNode> below = makeSwingingArm(1.0);
    osg::ref_ptr<osg::Group> attached = new osg::Group;
    osg::ref_ptr<CountingCallback> onAttached = new CountingCallback;
    attached->setUpdateCallback(onAttached.get());
    below->getSkeletonNode("tip")->addChild(attached.get());
    osg::ref_ptr<ActorNode> replaced = makeSwingingArm(2.0);
    osg::ref_ptr<CountingCallback> instead = new CountingCallback;
    replaced->setUpdateCallback(instead.get()); // no ActorUpdateCallback at all: the group still updates it
    osg::ref_ptr<osg::Group> other = new osg::Group;
    osg::ref_ptr<CountingCallback> onOther = new CountingCallback;
    other->setUpdateCallback(onOther.get());
    for (osg::Node* child : {static_cast<osg::Node*>(nested.get()), static_cast<osg::Node*>(below.get()),
                             static_cast<osg::Node*>(replaced.get()), static_cast<osg::Node*>(other.get())})
        group->addChild(child);
    for (unsigned frame = 1; frame <= 3; ++frame) runUpdate(*group, frame);
    EXPECT_EQ(onActor->calls, 3);
    EXPECT_EQ(onAttached->calls, 3);
    EXPECT_EQ(instead->calls, 3);
    EXPECT_EQ(onOther->calls, 3);
    for (ActorNode* actor : {nested.get(), below.get(), replaced.get()}) EXPECT_EQ(actor->getNumUpdatesRun(), 3u);
}

TEST(ActorGroup, FollowsItsChildrenAsTheyChange)
{
    osg::ref_ptr<ActorGroup> group = new ActorGroup;
    group->setNumThreads(2);
    osg::ref_ptr<ActorNode> first = makeSwingingArm(0.0);
    osg::ref_ptr<ActorNode> second = makeSwingingArm(1.0);
    osg::ref_ptr<ActorNode> third = makeSwingingArm(2.0);
    // A child many times over, among others: updated once a frame all the same, and never by two workers at
    // once (ThreadSanitizer runs this test).
    for (int copy = 0; copy < 16; ++copy)
    {
        group->addChild(first.get());
        group->addChild(makeSwingingArm(copy).get());
    }
    group->addChild(second.get());
    runUpdate(*group, 1);
    EXPECT_EQ(first->getNumUpdatesRun(), 1u);
    EXPECT_EQ(second->getNumUpdatesRun(), 1u);

    group->removeChild(second.get());
    group->addChild(third.get());
    runUpdate(*group, 2);
    EXPECT_EQ(first->getNumUpdatesRun(), 2u);
    EXPECT_EQ(second->getNumUpdatesRun(), 1u) << "removed: no longer updated";
    EXPECT_EQ(third->getNumUpdatesRun(), 1u) << "added: updated from its first frame in the group";

    group->replaceChild(third.get(), second.get()); // osg::Group::setChild() underneath
    runUpdate(*group, 3);
    EXPECT_EQ(third->getNumUpdatesRun(), 1u);
    EXPECT_EQ(second->getNumUpdatesRun(), 2u);
    EXPECT_EQ(first->getNumUpdatesRun(), 3u);
    const osg::Matrixd swung = second->getSkeletonNode(0u)->getMatrix();
    runUpdate(*group, 4);
    EXPECT_NE(second->getSkeletonNode(0u)->getMatrix(), swung) << "its controller runs in the group";
}

TEST(ActorGroup, PlacesActorsWhosePreTransformChangesBetweenFrames)
{
    // actor_m is written on the update thread, only for the actors whose placement changed.
    osg::ref_ptr<ActorGroup> group = new ActorGroup;
    group->setNumThreads(2);
    std::vector<osg::ref_ptr<ActorNode>> actors;
    for (int a = 0; a < 6; ++a)
    {
        actors.push_back(makeSwingingArm(a));
        actors.back()->getSkeletonNode("tip")->addChild(makeBox(osg::Vec3(), 0.1f).get());
        group->addChild(actors.back().get());
    }
    runUpdate(*group, 1);
    EXPECT_LT(group->getBound().center().x(), 4.0f);
    actors[3]->setPreTranslation(osg::Vec3d(50.0, 0.0, 0.0));
    runUpdate(*group, 2);
    EXPECT_EQ(actors[3]->getMatrix().getTrans(), osg::Vec3d(50.0, 0.0, 0.0));
    EXPECT_EQ(actors[2]->getMatrix().getTrans(), osg::Vec3d());
    EXPECT_GT(actors[3]->getBound().center().x(), 45.0f);
    EXPECT_TRUE(group->getBound().contains(actors[3]->getBound().center())) << "the group's bound was dirtied";
}
