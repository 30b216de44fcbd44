// Skinned characters, the whole frame, osgActor against osgAnimation in one run (issue 26, item 10): N = 1, 100 and
// 1000 Cesium Men playing the file's walk, built from the same import of the same file (SkinnedCrowds), in six
// systems: osgActor's SkinnedMesh on the GPU and on the CPU path, the GPU path in an InstancedActorGroup drawing
// ordinarily and instanced (skinned instancing, issue 28), osgAnimation's RigGeometry with RigTransformSoftware and
// with RigTransformHardware. Two modes:
//   update_cull  the update and cull traversals (osgUtil::SceneView, no graphics context): osgActor's skinning
//                matrices and bounds in update, its CPU skinning or palette upload in cull; osgAnimation's skinning
//                or palette in update;
//   frame_draw   update, cull and draw through OSMesa (llvmpipe, 320 x 240), the pixels read back: the GPU paths'
//                vertex shaders run on the CPU here. With OSGACTOR_BENCH_OUT set, each system's first frame is
//                written there as a PNG, to see that the peers draw the same crowd.
// Reported per frame; the run ends with a table of each system's time over osgAnimation's, and over the ordinary
// group's, at the same N and mode.
#include "SkinnedCrowds"

#include "../actors/FrameLoop"

#include <osgActor/Offscreen/OffscreenRenderer>

#include <benchmark/benchmark.h>

#include <osgDB/WriteFile>

#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>
#include <tuple>
#include <vector>

namespace {

using bench::SkinnedSystem;

const SkinnedSystem kSystems[] = {SkinnedSystem::OsgActorGpu,          SkinnedSystem::OsgActorCpu,
                                  SkinnedSystem::OsgActorGpuGroup,     SkinnedSystem::OsgActorGpuInstanced,
                                  SkinnedSystem::OsgAnimationSoftware, SkinnedSystem::OsgAnimationHardware};

std::string cesiumManFile() { return std::string(OSGACTOR_BENCH_DATA_DIR) + "/models/CesiumMan/CesiumMan.gltf"; }

/** Whether any pixel differs from the first one (the background): the crowd was drawn. */
bool drewSomething(const osg::Image& image)
{
    const unsigned char* first = image.data(0, 0);
    for (int y = 0; y < image.t(); ++y)
        for (int x = 0; x < image.s(); ++x)
            for (int c = 0; c < 3; ++c)
                if (image.data(x, y)[c] != first[c]) return true;
    return false;
}

void updateAndCull(benchmark::State& state, SkinnedSystem system)
{
    const unsigned n = static_cast<unsigned>(state.range(0));
    osg::ref_ptr<osg::Group> crowd = bench::makeSkinnedCrowd(system, n, cesiumManFile());
    if (!crowd)
    {
        state.SkipWithError("cannot build the crowd");
        return;
    }
    bench::FrameLoop loop(crowd.get(), true);
    for (int i = 0; i < 3; ++i) loop.frame(); // osgAnimation links its channels and builds its rigs on first frames
    // Instanced, one draw holds them all.
    if (loop.lastDrawables() != (system == SkinnedSystem::OsgActorGpuInstanced ? 1u : n))
    {
        state.SkipWithError("not every character was culled in");
        return;
    }
    for (auto _ : state) loop.frame();
    state.counters["ns_per_frame"] =
        benchmark::Counter(double(state.iterations()), benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

void frameAndDraw(benchmark::State& state, SkinnedSystem system)
{
    const unsigned n = static_cast<unsigned>(state.range(0));
    osg::ref_ptr<osg::Group> crowd = bench::makeSkinnedCrowd(system, n, cesiumManFile());
    std::string error;
    osg::ref_ptr<osgActor::OffscreenRenderer> renderer = osgActor::OffscreenRenderer::create(320, 240, error);
    if (!crowd || !renderer)
    {
        state.SkipWithError(crowd ? error.c_str() : "cannot build the crowd");
        return;
    }
    renderer->setScene(crowd.get());
    renderer->setViewMatrixAsLookAt(osg::Vec3d(2.0, -4.0, 1.2), osg::Vec3d(0, 0, 0.6), osg::Vec3d(0, 0, 1));
    double t = 0.0;
    osg::ref_ptr<osg::Image> image;
    for (int i = 0; i < 3; ++i) image = renderer->renderFrame(t += 1.0 / 60.0);
    if (!image || !drewSomething(*image))
    {
        state.SkipWithError("nothing was drawn");
        return;
    }
    // To see that the peers draw the same crowd: $OSGACTOR_BENCH_OUT/skin_draw_<system>_<N>.png.
    if (const char* out = std::getenv("OSGACTOR_BENCH_OUT"))
        osgDB::writeImageFile(*image, std::string(out) + "/skin_draw_" + bench::nameOf(system) + "_" +
                                          std::to_string(n) + ".png");
    for (auto _ : state) benchmark::DoNotOptimize(renderer->renderFrame(t += 1.0 / 60.0).get());
    state.counters["ns_per_frame"] =
        benchmark::Counter(double(state.iterations()), benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

/** Prints each run, and at the end each system's time per frame over osgAnimation's (software and hardware) at the
  * same mode and N. */
class RatioReporter : public benchmark::ConsoleReporter
{
public:
    void ReportRuns(const std::vector<Run>& runs) override
    {
        benchmark::ConsoleReporter::ReportRuns(runs);
        for (const Run& run : runs)
        {
            if (run.error_occurred || run.iterations == 0) continue;
            const std::string name = run.benchmark_name();
            const std::size_t a = name.find('/'), b = name.find('/', a + 1);
            if (a == std::string::npos || b == std::string::npos) continue;
            const std::string mode = name.substr(0, a), system = name.substr(a + 1, b - a - 1);
            const long n = std::atol(name.c_str() + b + 1);
            _nsPerFrame[std::make_tuple(mode, n, system)] = run.GetAdjustedRealTime() *
                                                             (run.time_unit == benchmark::kMillisecond ? 1e6 : 1e3);
        }
    }

    void printRatios() const
    {
        std::printf("\n%-12s %6s %-22s %16s %12s %12s %12s\n", "mode", "N", "system", "ns/frame", "/osgAnim sw",
                    "/osgAnim hw", "/gpu group");
        for (const auto& entry : _nsPerFrame)
        {
            const std::string& mode = std::get<0>(entry.first);
            const long n = std::get<1>(entry.first);
            const auto software = _nsPerFrame.find(std::make_tuple(mode, n, std::string("osgAnimation_software")));
            const auto hardware = _nsPerFrame.find(std::make_tuple(mode, n, std::string("osgAnimation_hardware")));
            // Instanced against the same group drawing ordinarily.
            const auto group = _nsPerFrame.find(std::make_tuple(mode, n, std::string("osgActor_gpu_group")));
            std::printf("%-12s %6ld %-22s %16.0f %12.3f %12.3f %12.3f\n", mode.c_str(), n,
                        std::get<2>(entry.first).c_str(), entry.second,
                        software != _nsPerFrame.end() ? entry.second / software->second : 0.0,
                        hardware != _nsPerFrame.end() ? entry.second / hardware->second : 0.0,
                        group != _nsPerFrame.end() ? entry.second / group->second : 0.0);
        }
    }

private:
    std::map<std::tuple<std::string, long, std::string>, double> _nsPerFrame;
};

void registerAll()
{
    // Interleaved: for each mode and N, every system in turn, so that drift in the machine's load hits them alike.
    for (int n : {1, 100, 1000})
        for (SkinnedSystem system : kSystems)
            benchmark::RegisterBenchmark((std::string("update_cull/") + bench::nameOf(system)).c_str(),
                                         [system](benchmark::State& state) { updateAndCull(state, system); })
                ->Arg(n)->Unit(benchmark::kMicrosecond)->UseRealTime();
    for (int n : {1, 100, 1000})
        for (SkinnedSystem system : kSystems)
            benchmark::RegisterBenchmark((std::string("frame_draw/") + bench::nameOf(system)).c_str(),
                                         [system](benchmark::State& state) { frameAndDraw(state, system); })
                ->Arg(n)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(n >= 1000 ? 2.0 : 0.5);
}

} // namespace

int main(int argc, char** argv)
{
    benchmark::Initialize(&argc, argv);
    registerAll();
    RatioReporter reporter;
    benchmark::RunSpecifiedBenchmarks(&reporter);
    reporter.printRatios();
    benchmark::Shutdown();
    return 0;
}
