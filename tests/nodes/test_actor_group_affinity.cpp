// The processors an ActorGroup's workers run on: osgViewer pins the thread that runs its frames to one processor,
// and the workers, made by that thread on the group's first update, must not inherit that.
#include "NodeTestUtil"

#include <osgActor/ActorGroup>

#include <OpenThreads/Thread>

#include <chrono>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#if defined(__linux__)
#include <sched.h>

using namespace osgActor;
using namespace osgActor::test;

namespace {

/** What the updates run on threads other than the test's saw: the processors their thread may run on. */
struct WorkerProcessors
{
    std::mutex mutex;
    std::vector<cpu_set_t> seen;
};

/** Records the affinity of each worker thread that updates its actor; spins a little per update, so that the
  * workers claim their share of a frame before the test's thread is done with its own. */
class AffinityProbe : public Controller
{
public:
    AffinityProbe(std::thread::id caller, std::shared_ptr<WorkerProcessors> seen) : _caller(caller), _seen(seen) {}
    void update(const ControllerContext&, ControllerTarget&) override
    {
        const auto until = std::chrono::steady_clock::now() + std::chrono::microseconds(200);
        while (std::chrono::steady_clock::now() < until) std::this_thread::yield();
        if (std::this_thread::get_id() == _caller) return;
        cpu_set_t processors;
        CPU_ZERO(&processors);
        sched_getaffinity(0, sizeof(processors), &processors);
        std::lock_guard<std::mutex> lock(_seen->mutex);
        _seen->seen.push_back(processors);
    }
    std::shared_ptr<Controller> cloneController() const override { return std::make_shared<AffinityProbe>(*this); }

private:
    std::thread::id _caller;
    std::shared_ptr<WorkerProcessors> _seen;
};

/** Pins the calling thread to its first allowed processor, as osgViewer's configureAffinity() pins the thread that
  * runs the frames, for the scope's life. */
class PinnedToOneProcessor
{
public:
    PinnedToOneProcessor()
    {
        CPU_ZERO(&_before);
        sched_getaffinity(0, sizeof(_before), &_before);
        cpu_set_t one;
        CPU_ZERO(&one);
        for (int cpu = 0; cpu < CPU_SETSIZE; ++cpu)
            if (CPU_ISSET(cpu, &_before))
            {
                CPU_SET(cpu, &one);
                break;
            }
        sched_setaffinity(0, sizeof(one), &one);
    }
    ~PinnedToOneProcessor() { sched_setaffinity(0, sizeof(_before), &_before); }

private:
    cpu_set_t _before;
};

/** 64 arms probed, under a group of two threads with the affinity given, updated until the workers have run some
  * (at most 50 frames); what they saw. */
std::vector<cpu_set_t> workerAffinities(const OpenThreads::Affinity& affinity)
{
    auto seen = std::make_shared<WorkerProcessors>();
    osg::ref_ptr<ActorGroup> group = new ActorGroup;
    group->setNumThreads(2);
    group->setWorkerAffinity(affinity);
    for (int a = 0; a < 64; ++a)
    {
        osg::ref_ptr<ActorNode> actor = new ActorNode(makePlanarArm());
        actor->addController(std::make_shared<AffinityProbe>(std::this_thread::get_id(), seen));
        group->addChild(actor.get());
    }
    for (unsigned frame = 1; frame <= 50; ++frame)
    {
        runUpdate(*group, frame);
        std::lock_guard<std::mutex> lock(seen->mutex);
        if (!seen->seen.empty()) break;
    }
    return seen->seen;
}

} // namespace

TEST(ActorGroupAffinity, WorkersRunOnEveryProcessorThoughTheThreadThatMadeThemIsPinned)
{
    const int processors = OpenThreads::GetNumberOfProcessors();
    if (processors < 2) GTEST_SKIP() << "one processor: nothing to pin away from";
    PinnedToOneProcessor pinned;
    const std::vector<cpu_set_t> seen = workerAffinities(OpenThreads::Affinity());
    ASSERT_FALSE(seen.empty()) << "no update ran on a worker in 50 frames";
    for (const cpu_set_t& set : seen) EXPECT_EQ(CPU_COUNT(&set), processors) << "a worker kept its maker's processor";
}

TEST(ActorGroupAffinity, WorkersRunOnTheProcessorsAsked)
{
    if (OpenThreads::GetNumberOfProcessors() < 2) GTEST_SKIP() << "one processor: nothing to choose";
    const std::vector<cpu_set_t> seen = workerAffinities(OpenThreads::Affinity(1));
    ASSERT_FALSE(seen.empty()) << "no update ran on a worker in 50 frames";
    for (const cpu_set_t& set : seen)
    {
        EXPECT_EQ(CPU_COUNT(&set), 1);
        EXPECT_TRUE(CPU_ISSET(1, &set));
    }
}

#endif // __linux__
