// The pose alone, no scene graph: a ClipPlayer sampling the clip into the DOF vector, and forward kinematics to
// model space, per joint (what ozz-animation's sampling and local-to-model jobs do).
#include "BenchHumanoid"
#include "NsPerJoint"
#include "PoseCrowd"

#include <osgActor/core/ActorPose>

#include <benchmark/benchmark.h>

#include <vector>

namespace {

void BM_CorePoseSampleAndFK(benchmark::State& state)
{
    const unsigned numActors = static_cast<unsigned>(state.range(0));
    bench::PoseCrowd crowd(numActors);
    for (auto _ : state)
    {
        crowd.frame();
        benchmark::ClobberMemory();
    }
    bench::reportNsPerJoint(state, numActors);
}
BENCHMARK(BM_CorePoseSampleAndFK)->Arg(1)->Arg(1000);

void BM_CoreFKOnly(benchmark::State& state)
{
    const unsigned numActors = static_cast<unsigned>(state.range(0));
    const osgActor::ActorDefinitionPtr def = bench::humanoidDefinition();
    std::vector<osgActor::ActorPose> poses(numActors, osgActor::ActorPose(def));
    for (auto _ : state)
    {
        for (unsigned a = 0; a < numActors; ++a)
        {
            poses[a].markAllJointsDirty();
            poses[a].updateMatrices();
        }
        benchmark::ClobberMemory();
    }
    bench::reportNsPerJoint(state, numActors);
}
BENCHMARK(BM_CoreFKOnly)->Arg(1)->Arg(1000);

} // namespace

BENCHMARK_MAIN();
