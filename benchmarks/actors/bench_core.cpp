// The pose alone, no scene graph: sampling the clip into the DOF vector and forward kinematics, per joint.
#include "BenchHumanoid"

#include <osgActor/core/ActorPose>

#include <benchmark/benchmark.h>

#include <vector>

namespace {

/** Samples the bench clip linearly at time t into a pose (DOF order: root rx ry rz tx ty tz, then rx ry rz). */
void sampleInto(const bench::BenchClip& clip, double t, osgActor::ActorPose& pose)
{
    const double frame = std::fmod(t, clip.duration()) * clip.framesPerSecond;
    const unsigned f0 = static_cast<unsigned>(frame);
    const unsigned f1 = std::min(f0 + 1, clip.numFrames - 1);
    const double alpha = frame - f0;
    unsigned dof = 0;
    for (unsigned j = 0; j < clip.jointCount; ++j)
    {
        const double* a0 = clip.anglesAt(f0, j);
        const double* a1 = clip.anglesAt(f1, j);
        for (unsigned a = 0; a < 3; ++a) pose.setDof(dof++, a0[a] + alpha * (a1[a] - a0[a]));
        if (j == 0)
            for (unsigned a = 0; a < 3; ++a)
                pose.setDof(dof++, clip.rootPosition[f0 * 3 + a] +
                                       alpha * (clip.rootPosition[f1 * 3 + a] - clip.rootPosition[f0 * 3 + a]));
    }
}

void BM_CorePoseSampleAndFK(benchmark::State& state)
{
    const unsigned numActors = static_cast<unsigned>(state.range(0));
    const osgActor::ActorDefinitionPtr def = bench::humanoidDefinition();
    std::vector<osgActor::ActorPose> poses(numActors, osgActor::ActorPose(def));
    const bench::BenchClip& clip = bench::humanoidClip();
    double t = 0.0;
    for (auto _ : state)
    {
        t += 1.0 / 60.0;
        for (unsigned a = 0; a < numActors; ++a)
        {
            sampleInto(clip, t + 0.01 * a, poses[a]);
            poses[a].updateMatrices();
        }
        benchmark::ClobberMemory();
    }
    const double joints = static_cast<double>(numActors) * def->getNumJoints();
    state.counters["ns_per_joint"] =
        benchmark::Counter(joints, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_CorePoseSampleAndFK)->Arg(1)->Arg(1000);

void BM_CoreFKOnly(benchmark::State& state)
{
    const unsigned numActors = static_cast<unsigned>(state.range(0));
    const osgActor::ActorDefinitionPtr def = bench::humanoidDefinition();
    std::vector<osgActor::ActorPose> poses(numActors, osgActor::ActorPose(def));
    const bench::BenchClip& clip = bench::humanoidClip();
    for (unsigned a = 0; a < numActors; ++a) sampleInto(clip, 0.3 + 0.01 * a, poses[a]);
    for (auto _ : state)
    {
        for (unsigned a = 0; a < numActors; ++a)
        {
            poses[a].markAllJointsDirty();
            poses[a].updateMatrices();
        }
        benchmark::ClobberMemory();
    }
    const double joints = static_cast<double>(numActors) * def->getNumJoints();
    state.counters["ns_per_joint"] =
        benchmark::Counter(joints, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_CoreFKOnly)->Arg(1)->Arg(1000);

} // namespace

BENCHMARK_MAIN();
