// The pose alone, no scene graph: a ClipPlayer sampling the clip into the DOF vector, and forward kinematics to
// model space, per joint (what ozz-animation's sampling and local-to-model jobs do).
#include "BenchHumanoid"

#include <osgActor/core/ActorPose>
#include <osgActor/core/ClipPlayer>

#include <benchmark/benchmark.h>

#include <vector>

namespace {

/** Reports the run's time per joint of numActors humanoids. */
void countJoints(benchmark::State& state, unsigned numActors, const osgActor::ActorDefinition& def)
{
    const double joints = static_cast<double>(numActors) * def.getNumJoints();
    state.counters["ns_per_joint"] =
        benchmark::Counter(joints, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

void BM_CorePoseSampleAndFK(benchmark::State& state)
{
    const unsigned numActors = static_cast<unsigned>(state.range(0));
    const osgActor::ActorDefinitionPtr def = bench::humanoidDefinition();
    std::vector<osgActor::ActorPose> poses(numActors, osgActor::ActorPose(def));
    std::vector<osgActor::ActorTransforms> transforms(numActors);
    std::vector<std::vector<osgActor::ControllerPtr>> players(numActors);
    for (unsigned a = 0; a < numActors; ++a)
    {
        auto player = std::make_shared<osgActor::ClipPlayer>(bench::humanoidOsgActorClip());
        player->setPlayMode(osgActor::PlayMode::Loop);
        player->seek(0.01 * a);
        player->play();
        players[a].push_back(player);
    }
    osgActor::ControllerContext context;
    context.deltaTime = 1.0 / 60.0;
    for (auto _ : state)
    {
        context.time += context.deltaTime;
        for (unsigned a = 0; a < numActors; ++a)
        {
            osgActor::ControllerTarget target{poses[a], transforms[a]};
            osgActor::runControllers(players[a], context, target);
            poses[a].updateMatrices(); // local and model matrices, as ozz-animation's sampling + local-to-model
        }
        benchmark::ClobberMemory();
    }
    countJoints(state, numActors, *def);
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
    countJoints(state, numActors, *def);
}
BENCHMARK(BM_CoreFKOnly)->Arg(1)->Arg(1000);

} // namespace

BENCHMARK_MAIN();
