// osgActor against osgAnimation and plain OSG, side by side in one run: the same 31-joint humanoid and the same
// looping clip in each system, N = 1, 10, 100, 1000 instances, the update traversal alone and update plus cull.
// Reported per joint; the summary at the end gives each result's ratio to osgAnimation at the same N and mode.
#include "BenchReport"
#include "FrameLoop"
#include "NsPerJoint"
#include "PeerScenes"

#include <benchmark/benchmark.h>

#include <osg/MatrixTransform>

namespace {

using bench::Motion;

enum class System { OsgActorAll, OsgActorQuarter, OsgActorIdle, OsgAnimation, PlainOsg, OsgActorAllFollow,
                    OsgActor1Thread, OsgActor2Threads };

osg::ref_ptr<osg::Group> makeScene(System system, unsigned numActors)
{
    switch (system)
    {
    case System::OsgActorAll: return bench::makeOsgActorScene(numActors, Motion::All);
    case System::OsgActorQuarter: return bench::makeOsgActorScene(numActors, Motion::Quarter);
    case System::OsgActorIdle: return bench::makeOsgActorScene(numActors, Motion::Idle);
    case System::OsgAnimation: return bench::makeOsgAnimationScene(numActors);
    case System::PlainOsg: return bench::makePlainOsgScene(numActors);
    case System::OsgActorAllFollow:
        return bench::makeOsgActorScene(numActors, Motion::All, 0, bench::Bounds::FollowPose);
    case System::OsgActor1Thread: return bench::makeOsgActorScene(numActors, Motion::All, 1);
    case System::OsgActor2Threads: return bench::makeOsgActorScene(numActors, Motion::All, 2);
    }
    return nullptr;
}

/** A sum over every transform matrix of the last instance: it changes when any joint of that instance moves. */
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
    scene.getChild(scene.getNumChildren() - 1)->accept(summer);
    return summer.sum;
}

void runSystem(benchmark::State& state, System system, bool withCull)
{
    const unsigned numActors = static_cast<unsigned>(state.range(0));
    osg::ref_ptr<osg::Group> scene = makeScene(system, numActors);
    bench::FrameLoop loop(scene.get(), withCull);
    // Warm up (osgAnimation links its channels on the first frame) and check that the system moves.
    loop.frame();
    const double before = poseSignature(*scene);
    for (int i = 0; i < 5; ++i) loop.frame();
    const bool moves = poseSignature(*scene) != before;
    if (moves != (system != System::OsgActorIdle))
    {
        state.SkipWithError(moves ? "the idle actor moved" : "the system does not animate its instances");
        return;
    }
    for (auto _ : state) loop.frame();
    bench::reportNsPerJoint(state, numActors);
    if (withCull) state.counters["drawables"] = loop.lastDrawables();
}

const char* const kNames[] = {"osgActor_all", "osgActor_quarter",   "osgActor_idle",    "osgAnimation",
                              "plainOSG",     "osgActor_all_follow", "osgActor_1thread", "osgActor_2threads"};

void registerAll()
{
    // Interleaved: for each N and mode, every system in turn, so drift in machine load hits all of them alike.
    for (bool withCull : {false, true})
        for (int n : {1, 10, 100, 1000})
            for (int s = 0; s < 6; ++s)
            {
                const System system = static_cast<System>(s);
                const std::string name = std::string(withCull ? "update_cull/" : "update/") + kNames[s];
                benchmark::RegisterBenchmark(name.c_str(), [system, withCull](benchmark::State& state) {
                    runSystem(state, system, withCull);
                })->Arg(n)->Unit(benchmark::kMicrosecond);
            }
    // Many actors in an ActorGroup on one thread and on two: the update traversal, wall-clock time.
    for (int s : {6, 7})
    {
        const System system = static_cast<System>(s);
        benchmark::RegisterBenchmark((std::string("parallel/") + kNames[s]).c_str(), [system](benchmark::State& state) {
            runSystem(state, system, false);
        })->Arg(1000)->Unit(benchmark::kMicrosecond)->UseRealTime();
    }
}

} // namespace

int main(int argc, char** argv)
{
    benchmark::Initialize(&argc, argv);
    registerAll();
    bench::registerMemoryBenchmarks();
    bench::SummaryReporter reporter;
    benchmark::RunSpecifiedBenchmarks(&reporter);
    reporter.writeSummary();
    benchmark::Shutdown();
    return 0;
}
