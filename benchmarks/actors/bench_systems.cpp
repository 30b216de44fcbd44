// osgActor against osgAnimation and plain OSG, side by side in one run: the same 31-joint humanoid and the same
// looping clip in each system, N = 1, 10, 100, 1000 instances (--actors=N,...: up to 16000), the update traversal
// alone and update plus cull; the frame with every instance in view and with three in four behind the camera; the
// update, and update plus cull, of the largest crowd in an ActorGroup on 1, 2, 4, ... threads up to the machine's
// cores (--threads=N,...). Reported per joint; the summary at the end gives each result's ratio to osgAnimation at the
// same N and mode, and each system's frame in view against its frame with three in four out of view.
#include "BenchReport"
#include "CountList"
#include "FrameLoop"
#include "NsPerJoint"
#include "PeerScenes"

#include <benchmark/benchmark.h>

#include <osgActor/ActorGroup>

#include <osg/MatrixTransform>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <thread>
#include <vector>

namespace {

using bench::Motion;

enum class System { OsgActorAll, OsgActorAllNodeByNode, OsgActorQuarter, OsgActorIdle, OsgAnimation, PlainOsg,
                    OsgActorAllFollow, OsgActorAllInstanced, OsgActorIdleInstanced, OsgActorQuarterInstanced };
constexpr int kNumSystems = 10;

const char* const kNames[kNumSystems] = {"osgActor_all", "osgActor_all_nodebynode", "osgActor_quarter",
                                         "osgActor_idle", "osgAnimation",            "plainOSG",
                                         "osgActor_all_follow", "osgActor_all_instanced", "osgActor_idle_instanced",
                                         "osgActor_quarter_instanced"};

/** A system's crowd; outOfView: the share of its instances behind the camera, where osgActor's actors follow
  * ActorNode::UpdatePolicy::onlyWhenSeen (the peers have no such thing). */
osg::ref_ptr<osg::Group> makeScene(System system, unsigned numActors, double outOfView = -1.0)
{
    bench::OsgActorCrowd crowd;
    if (outOfView >= 0.0)
    {
        crowd.outOfView = outOfView;
        crowd.onlyWhenSeen = true;
    }
    osg::ref_ptr<osg::Group> scene;
    switch (system)
    {
    case System::OsgActorAll: return bench::makeOsgActorScene(numActors, crowd);
    case System::OsgActorAllNodeByNode: crowd.cullNodeByNode = true; return bench::makeOsgActorScene(numActors, crowd);
    case System::OsgActorQuarter: crowd.motion = Motion::Quarter; return bench::makeOsgActorScene(numActors, crowd);
    case System::OsgActorIdle: crowd.motion = Motion::Idle; return bench::makeOsgActorScene(numActors, crowd);
    case System::OsgActorAllFollow:
        crowd.bounds = bench::Bounds::FollowPose;
        return bench::makeOsgActorScene(numActors, crowd);
    case System::OsgActorAllInstanced: crowd.instanced = true; return bench::makeOsgActorScene(numActors, crowd);
    case System::OsgActorIdleInstanced:
        crowd.instanced = true;
        crowd.motion = Motion::Idle;
        return bench::makeOsgActorScene(numActors, crowd);
    case System::OsgActorQuarterInstanced:
        crowd.instanced = true;
        crowd.motion = Motion::Quarter;
        return bench::makeOsgActorScene(numActors, crowd);
    case System::OsgAnimation: scene = bench::makeOsgAnimationScene(numActors); break;
    case System::PlainOsg: scene = bench::makePlainOsgScene(numActors); break;
    }
    if (outOfView >= 0.0) bench::placeInstances(*scene, outOfView);
    return scene;
}

/** A sum over every transform matrix of the first instance (always in view): it changes when any joint of that
  * instance moves. */
double poseSignature(osg::Group& scene)
{
    struct Summer : osg::NodeVisitor
    {
        Summer() : osg::NodeVisitor(TRAVERSE_ALL_CHILDREN) {}
        void apply(osg::MatrixTransform& transform) override
        {
            for (int i = 0; i < 16; ++i) sum += transform.getMatrix().ptr()[i] * (i + 1);
            traverse(transform);
        }
        double sum = 0.0;
    } summer;
    scene.getChild(0)->accept(summer);
    return summer.sum;
}

void runScene(benchmark::State& state, osg::Group& scene, bool withCull, bool shouldMove,
              bench::FrameLoop::NearFar nearFar = bench::FrameLoop::NearFar::NotComputed)
{
    const unsigned numActors = static_cast<unsigned>(state.range(0));
    bench::FrameLoop loop(&scene, withCull, nearFar);
    // Warm up (osgAnimation links its channels on the first frame) and check that the system moves.
    loop.frame();
    const double before = poseSignature(scene);
    for (int i = 0; i < 5; ++i) loop.frame();
    const bool moves = poseSignature(scene) != before;
    if (moves != shouldMove)
    {
        state.SkipWithError(moves ? "the idle actor moved" : "the system does not animate its instances");
        return;
    }
    for (auto _ : state) loop.frame();
    bench::reportNsPerJoint(state, numActors);
    if (withCull) state.counters["drawables"] = loop.lastDrawables();
}

/** What the command line chose: the crowd sizes and the thread counts of the parallel sweep. */
struct Sweep
{
    std::vector<int> actors{1, 10, 100, 1000};
    std::vector<int> threads;
};

void registerAll(const Sweep& sweep)
{
    // Interleaved: for each N and mode, every system in turn, so drift in machine load hits all of them alike.
    for (bool withCull : {false, true})
        for (int n : sweep.actors)
            for (int s = 0; s < kNumSystems; ++s)
            {
                const System system = static_cast<System>(s);
                // The node-by-node cull has the same update as _all; the instanced group (InstancedActorGroup, one
                // thread) only another cull.
                if ((system == System::OsgActorAllNodeByNode || system == System::OsgActorAllInstanced ||
                     system == System::OsgActorIdleInstanced || system == System::OsgActorQuarterInstanced) &&
                    !withCull)
                    continue;
                const std::string name = std::string(withCull ? "update_cull/" : "update/") + kNames[s];
                benchmark::RegisterBenchmark(name.c_str(), [system, withCull](benchmark::State& state) {
                    osg::ref_ptr<osg::Group> scene = makeScene(system, static_cast<unsigned>(state.range(0)));
                    runScene(state, *scene, withCull,
                             system != System::OsgActorIdle && system != System::OsgActorIdleInstanced);
                })->Arg(n)->Unit(benchmark::kMicrosecond);
            }
    // Update + cull with osgViewer's default camera: near and far computed from bounding volumes.
    for (int n : sweep.actors)
        for (System system : {System::OsgActorAll, System::OsgActorIdle, System::OsgActorAllInstanced,
                              System::OsgActorIdleInstanced, System::OsgAnimation, System::PlainOsg})
        {
            const std::string name = std::string("update_cull_nearfar/") + kNames[int(system)];
            benchmark::RegisterBenchmark(name.c_str(), [system](benchmark::State& state) {
                osg::ref_ptr<osg::Group> scene = makeScene(system, static_cast<unsigned>(state.range(0)));
                runScene(state, *scene, true,
                         system != System::OsgActorIdle && system != System::OsgActorIdleInstanced,
                         bench::FrameLoop::NearFar::FromBoundingVolumes);
            })->Arg(n)->Unit(benchmark::kMicrosecond);
        }
    // The whole frame (update + cull) with every instance in view, and with three in four behind the camera; each
    // instance under a placing transform in both (osgActor's actors placed by their pre-translation, under an
    // InstancedActorGroup too), osgActor's actors updating only when seen.
    for (int n : sweep.actors)
    {
        if (n < 4) continue;
        for (double share : {0.0, 0.75})
            for (System system :
                 {System::OsgActorAll, System::OsgActorAllInstanced, System::OsgAnimation, System::PlainOsg})
            {
                const std::string name =
                    std::string(share > 0.0 ? "frame_quarter_in_view/" : "frame_in_view/") + kNames[int(system)];
                benchmark::RegisterBenchmark(name.c_str(), [system, share](benchmark::State& state) {
                    osg::ref_ptr<osg::Group> scene = makeScene(system, static_cast<unsigned>(state.range(0)), share);
                    runScene(state, *scene, true, true);
                })->Arg(n)->Unit(benchmark::kMicrosecond);
            }
    }
    // The largest crowd in an ActorGroup on each thread count: the update traversal, wall-clock time. One crowd
    // for the whole sweep, its thread count changed between runs, and never destroyed: every joint of every actor
    // holds the one shared box geode, and OSG removes a parent from a node's parent list by a linear search and
    // erase, so taking a crowd of 16,000 apart (500,000 parents of one node) costs far more than the sweep itself.
    // The same with the cull (parallel_cull: update + cull, the actors' cull prepared on the group's threads).
    const int largest = *std::max_element(sweep.actors.begin(), sweep.actors.end());
    for (bool withCull : {false, true})
        for (int threads : sweep.threads)
        {
            const std::string name = std::string(withCull ? "parallel_cull" : "parallel") + "/osgActor_" +
                                     std::to_string(threads) + (threads == 1 ? "thread" : "threads");
            benchmark::RegisterBenchmark(name.c_str(), [threads, withCull](benchmark::State& state) {
                static osgActor::ActorGroup* const crowd = [&state] {
                    osg::ref_ptr<osg::Group> scene =
                        bench::makeOsgActorScene(static_cast<unsigned>(state.range(0)), Motion::All, 1u);
                    scene->ref(); // the reference that is never given back
                    return static_cast<osgActor::ActorGroup*>(scene.get());
                }();
                crowd->setNumThreads(unsigned(threads));
                runScene(state, *crowd, withCull, true);
            })->Arg(largest)->Unit(benchmark::kMicrosecond)->UseRealTime();
        }
    // The same crowd under an InstancedActorGroup, update + cull (parallel_cull_instanced: each actor's part of the
    // instanced cull, its instances' data included, on the group's threads), its own crowd kept as the one above.
    for (int threads : sweep.threads)
    {
        const std::string name = std::string("parallel_cull_instanced/osgActor_") + std::to_string(threads) +
                                  (threads == 1 ? "thread" : "threads");
        benchmark::RegisterBenchmark(name.c_str(), [threads](benchmark::State& state) {
            static osgActor::ActorGroup* const crowd = [&state] {
                bench::OsgActorCrowd instanced;
                instanced.instanced = true;
                osg::ref_ptr<osg::Group> scene =
                    bench::makeOsgActorScene(static_cast<unsigned>(state.range(0)), instanced);
                scene->ref(); // the reference that is never given back
                return static_cast<osgActor::ActorGroup*>(scene.get());
            }();
            crowd->setNumThreads(unsigned(threads));
            runScene(state, *crowd, true, true);
        })->Arg(largest)->Unit(benchmark::kMicrosecond)->UseRealTime();
    }
}

/** Takes --actors=N,... and --threads=N,... out of the arguments (Google Benchmark's own stay); false, with a
  * message, on a bad value. */
bool parseSweep(int& argc, char** argv, Sweep& sweep)
{
    const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
    for (unsigned t = 1; t < cores; t *= 2) sweep.threads.push_back(static_cast<int>(t));
    sweep.threads.push_back(static_cast<int>(cores));
    int kept = 1;
    for (int i = 1; i < argc; ++i)
    {
        const std::string argument = argv[i];
        std::vector<int>* target = argument.rfind("--actors=", 0) == 0    ? &sweep.actors
                                   : argument.rfind("--threads=", 0) == 0 ? &sweep.threads
                                                                           : nullptr;
        if (!target)
        {
            argv[kept++] = argv[i];
            continue;
        }
        if (!bench::parseCountList(argv[i] + argument.find('=') + 1, 16000, *target))
        {
            std::fprintf(stderr, "osgactorbench: %s: want a list of counts in 1..16000, such as 1,10,100,1000\n",
                         argv[i]);
            return false;
        }
    }
    argc = kept;
    return true;
}

} // namespace

int main(int argc, char** argv)
{
    Sweep sweep;
    if (!parseSweep(argc, argv, sweep)) return 2;
    benchmark::Initialize(&argc, argv);
    registerAll(sweep);
    bench::registerMemoryBenchmarks();
    bench::SummaryReporter reporter;
    benchmark::RunSpecifiedBenchmarks(&reporter);
    reporter.writeSummary();
    benchmark::Shutdown();
    return 0;
}
