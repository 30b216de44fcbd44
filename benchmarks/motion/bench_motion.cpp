/* Motion benchmarks: BVH loading against OSG's own osgdb_bvh on the same files in the same run, and clip sampling
 * (with and without forward kinematics) per joint.
 *
 *   build/bin/osgactor_motion_bench                 all of them
 *   build/bin/osgactor_motion_bench --benchmark_filter=Ratio
 *
 * BM_BvhLoadRatio times both loaders back to back inside each iteration and reports osgdb_bvh's time over ours
 * as the counter "osg_over_ours". */
#include <osgActor/core/ActorPose>
#include <osgActor/core/ClipBuilder>
#include <osgActor/core/ClipPlayer>
#include <osgActor/core/SamplingJob>
#include <osgActor/mocap/BvhReader>

#include <osgDB/ReadFile>
#include <osgDB/Registry>

#include <benchmark/benchmark.h>

#include <chrono>
#include <string>
#include <vector>

using namespace osgActor;

namespace {

const std::vector<std::string>& bvhFiles()
{
    static const std::vector<std::string> files = {
        std::string(OSGACTOR_BENCH_MOCAP_DIR) + "/bvh/12_03.bvh",
        "/usr/share/assimp/models/BVH/01_01.bvh",
        "/usr/share/assimp/models/BVH/Boxing_Toes.bvh",
    };
    return files;
}

std::string shortName(const std::string& path) { return path.substr(path.find_last_of('/') + 1); }

osg::ref_ptr<osgDB::Options> noCache()
{
    osg::ref_ptr<osgDB::Options> options = new osgDB::Options;
    options->setObjectCacheHint(osgDB::Options::CACHE_NONE);
    return options;
}

void BM_BvhLoad_osgActor(benchmark::State& state)
{
    const std::string& path = bvhFiles()[static_cast<std::size_t>(state.range(0))];
    state.SetLabel(shortName(path));
    for (auto _ : state)
    {
        MocapImport imported = readBvhFile(path);
        if (!imported) state.SkipWithError(imported.error.c_str());
        benchmark::DoNotOptimize(imported.clip);
    }
}

void BM_BvhLoad_osgdb_bvh(benchmark::State& state)
{
    const std::string& path = bvhFiles()[static_cast<std::size_t>(state.range(0))];
    state.SetLabel(shortName(path));
    osg::ref_ptr<osgDB::Options> options = noCache();
    osgDB::readRefNodeFile(path, options.get()); // loads the plugin outside the timing
    for (auto _ : state)
    {
        osg::ref_ptr<osg::Node> node = osgDB::readRefNodeFile(path, options.get());
        if (!node) state.SkipWithError("osgdb_bvh could not read the file");
        benchmark::DoNotOptimize(node.get());
    }
}

void BM_BvhLoadRatio(benchmark::State& state)
{
    const std::string& path = bvhFiles()[static_cast<std::size_t>(state.range(0))];
    state.SetLabel(shortName(path));
    osg::ref_ptr<osgDB::Options> options = noCache();
    osgDB::readRefNodeFile(path, options.get());
    double ours = 0.0, theirs = 0.0;
    using Clock = std::chrono::steady_clock;
    for (auto _ : state)
    {
        const Clock::time_point a = Clock::now();
        MocapImport imported = readBvhFile(path);
        const Clock::time_point b = Clock::now();
        osg::ref_ptr<osg::Node> node = osgDB::readRefNodeFile(path, options.get());
        const Clock::time_point c = Clock::now();
        benchmark::DoNotOptimize(imported.clip);
        benchmark::DoNotOptimize(node.get());
        ours += std::chrono::duration<double>(b - a).count();
        theirs += std::chrono::duration<double>(c - b).count();
    }
    state.counters["ours_ms"] = 1e3 * ours / static_cast<double>(state.iterations());
    state.counters["osg_ms"] = 1e3 * theirs / static_cast<double>(state.iterations());
    state.counters["osg_over_ours"] = theirs / ours;
}

/** The CMU walk as a uniform clip (Y-up turned Z-up, as an application loads it). */
const MocapImport& walk()
{
    static const MocapImport imported = readBvhFile(std::string(OSGACTOR_BENCH_MOCAP_DIR) + "/bvh/12_03.bvh");
    return imported;
}

/** Sampling every channel of a uniform clip at a time between frames, reported per joint. */
void BM_ClipSampleUniform(benchmark::State& state)
{
    const Clip& clip = *walk().clip;
    ClipCursor cursor;
    clip.initCursor(cursor);
    std::vector<double> values(clip.getNumChannels());
    double time = 0.0;
    const double step = 1.0 / 97.0; // not a multiple of the frame time: always interpolates
    for (auto _ : state)
    {
        sampleEveryChannel(clip, time, cursor, values);
        benchmark::DoNotOptimize(values.data());
        time += step;
        if (time > clip.getDuration()) time = 0.0;
    }
    state.counters["ns_per_joint"] =
        benchmark::Counter(walk().definition->getNumJoints() * static_cast<double>(state.iterations()),
                           benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

/** The same motion as keyed cubic channels (one key per frame), sampled forwards with the cursor. */
void BM_ClipSampleKeyedCubic(benchmark::State& state)
{
    const Clip& uniform = *walk().clip;
    ClipBuilder builder("keyed");
    for (unsigned c = 0; c < uniform.getNumChannels(); ++c)
    {
        builder.addChannel(uniform.getChannel(c).target, Interpolation::Cubic);
        for (unsigned f = 0; f < uniform.getNumFrames(); ++f)
            builder.addKey(c, f / uniform.getFrameRate(), uniform.getFrame(f)[c]);
    }
    const ClipPtr clip = builder.build().clip;
    ClipCursor cursor;
    clip->initCursor(cursor);
    std::vector<double> values(clip->getNumChannels());
    double time = 0.0;
    for (auto _ : state)
    {
        sampleEveryChannel(*clip, time, cursor, values);
        benchmark::DoNotOptimize(values.data());
        time += 1.0 / 97.0;
        if (time > clip->getDuration()) time = 0.0;
    }
    state.counters["ns_per_joint"] =
        benchmark::Counter(walk().definition->getNumJoints() * static_cast<double>(state.iterations()),
                           benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

/** A ClipPlayer writing the pose and forward kinematics of every joint: the per-frame cost of a playing actor. */
void BM_ClipPlayerAndForwardKinematics(benchmark::State& state)
{
    ActorPose pose(walk().definition);
    ActorTransforms transforms;
    ClipPlayer player(walk().clip);
    ControllerContext context;
    context.deltaTime = 1.0 / 97.0;
    for (auto _ : state)
    {
        ControllerTarget target{pose, transforms};
        player.update(context, target);
        pose.updateMatrices();
        benchmark::DoNotOptimize(pose.getModelMatrix(0));
    }
    state.counters["ns_per_joint"] =
        benchmark::Counter(walk().definition->getNumJoints() * static_cast<double>(state.iterations()),
                           benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

} // namespace

BENCHMARK(BM_BvhLoad_osgActor)->DenseRange(0, 2)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_BvhLoad_osgdb_bvh)->DenseRange(0, 2)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_BvhLoadRatio)->DenseRange(0, 2)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ClipSampleUniform);
BENCHMARK(BM_ClipSampleKeyedCubic);
BENCHMARK(BM_ClipPlayerAndForwardKinematics);

BENCHMARK_MAIN();
