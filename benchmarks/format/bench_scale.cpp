/* Large inputs (issue 25, item 4): actors of 10^3, 10^4 and 10^5 joints, wide (one root, every other joint its child)
 * and deep (chains as deep as a skeleton may be), through each step of their life: reading the .actor text, building
 * the ActorNode, loading the file through osgDB's plugin (both), osgUtil::Optimizer as osgviewer and osgconv run it on
 * what they load, writing the .actor text through the plugin, and the first frame (update and cull); and BVH and AMC
 * motion of 10^3 to 10^5 frames read. The summary gives, for each, the growth of the time per tenfold size (linear
 * work: 10) and the peak resident memory per joint or frame (ScaleReport). The inputs are made at run time
 * (LargeInputs); run with OSG_LIBRARY_PATH=build/lib so that osgDB finds the plugins:
 *
 *     OSG_LIBRARY_PATH=build/lib build/bin/osgactor_scale_bench
 *     OSG_LIBRARY_PATH=build/lib OSGACTOR_SCALE_SIZES=30000,100000,300000 build/bin/osgactor_scale_bench
 *     OSG_LIBRARY_PATH=build/lib OSGACTOR_SCALE_HEAP=warm build/bin/osgactor_scale_bench   (see warmHeap())
 */
#include "AllocationCount"
#include "FrameLoop"
#include "LargeInputs"
#include "ResidentPeak"
#include "ScaleReport"

#include <osgActor/ActorNode>
#include <osgActor/ActorSceneIO>
#include <osgActor/io/ActorReader>
#include <osgActor/mocap/AmcReader>
#include <osgActor/mocap/AsfReader>
#include <osgActor/mocap/BvhReader>

#include <osg/Group>
#include <osgDB/FileUtils>
#include <osgDB/ReadFile>
#include <osgDB/Registry>
#include <osgUtil/Optimizer>

#include <benchmark/benchmark.h>

#include <malloc.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <memory>
#include <sstream>
#include <string>

using namespace bench;
using namespace osgActor;

namespace {

/** The sizes: 10^3, 10^4 and 10^5, or those OSGACTOR_SCALE_SIZES lists ("1000,100000,300000"), whose growth the
  * summary gives where a size and ten times it are both there. */
const std::vector<int64_t>& sizes()
{
    static const std::vector<int64_t> list = [] {
        std::vector<int64_t> values;
        std::istringstream in(std::getenv("OSGACTOR_SCALE_SIZES") ? std::getenv("OSGACTOR_SCALE_SIZES") : "");
        for (std::string item; std::getline(in, item, ',');)
            if (std::atol(item.c_str()) >= 2) values.push_back(std::atol(item.c_str()));
        return values.empty() ? std::vector<int64_t>{1000, 10000, 100000} : values;
    }();
    return list;
}

/** Whether the timed runs find the memory they take already mapped (OSGACTOR_SCALE_HEAP=warm: a program that loads
  * again and again) or not (the default, cold: each run starts as a program's first load does). Either way every
  * size is measured alike: left to itself, the allocator would keep what a small size freed for its next run (no page
  * faults) but give a large size's blocks back to the system (every run faulting them in again), and the growth per
  * tenfold would count the difference. */
bool warmHeap()
{
    static const bool warm = [] {
        const char* heap = std::getenv("OSGACTOR_SCALE_HEAP");
        if (!heap || std::string(heap) != "warm") return false;
        // Nothing given back to the system: no block mapped on its own, no trimming of the heap's top.
        mallopt(M_MMAP_THRESHOLD, 1 << 30);
        mallopt(M_TRIM_THRESHOLD, 1 << 30);
        return true;
    }();
    return warm;
}

/** The .actor text of a shape and size, made once. */
const std::string& actorText(SkeletonShape shape, unsigned joints)
{
    static std::map<std::pair<SkeletonShape, unsigned>, std::string> texts;
    std::string& text = texts[{shape, joints}];
    if (text.empty()) text = largeActorText(shape, joints);
    return text;
}

/** A file holding actorText(), written once into the temporary folder. */
std::string actorFile(SkeletonShape shape, unsigned joints)
{
    const char* folder = std::getenv("TMPDIR");
    const std::string path = std::string(folder ? folder : "/tmp") + "/osgactor_scale_" + shapeName(shape) + "_" +
                             std::to_string(joints) + ".actor";
    static std::map<std::string, bool> written;
    if (!written[path]) std::ofstream(path) << actorText(shape, joints);
    written[path] = true;
    return path;
}

ActorReadResult readText(const std::string& text)
{
    std::istringstream in(text);
    return readActor(in, "large.actor");
}

osg::ref_ptr<ActorNode> loadActor(const std::string& path)
{
    return dynamic_cast<ActorNode*>(osgDB::readRefNodeFile(path).get());
}

/** Times work(setup()) with setup() outside the timing, after one run outside it too that measures, per item
  * (state.range(0) items), the peak resident memory, what the result still holds and the heap allocations made; the
  * timed runs, each started with the freed memory given back to the system, count the minor page faults they take
  * (per item and run). work returns what it made, or null (or
  * false) on failure. */
template <class Setup, class Work>
void measure(benchmark::State& state, Setup setup, Work work)
{
    const double items = static_cast<double>(state.range(0));
    {
        auto input = setup();
        ResidentPeak peak;
        AllocationCount counts;
        auto output = work(input);
        const double allocations = static_cast<double>(counts.allocations());
        if (!output)
        {
            state.SkipWithError("the operation failed");
            return;
        }
        state.counters[kPeakBytesPerItem] = static_cast<double>(peak.peakBytes()) / items;
        state.counters[kHeldBytesPerItem] = static_cast<double>(peak.heldBytes()) / items;
        state.counters[kAllocationsPerItem] = allocations / items;
    }
    double faults = 0.0;
    for (auto _ : state)
    {
        state.PauseTiming();
        auto input = setup();
        if (!warmHeap()) malloc_trim(0); // after the setup, whose own freed memory the work would otherwise reuse
        const AllocationCount during;
        state.ResumeTiming();
        auto output = work(input);
        state.PauseTiming(); // freeing what it made is not part of the operation
        faults += static_cast<double>(during.minorFaults());
        benchmark::DoNotOptimize(output);
        output = decltype(output)();
        input = decltype(input)();
        state.ResumeTiming();
    }
    state.counters[kMinorFaultsPerItem] = faults / static_cast<double>(state.iterations()) / items;
    state.SetItemsProcessed(static_cast<int64_t>(state.iterations()) * state.range(0));
}

void registerActorBenchmarks(SkeletonShape shape)
{
    const std::string kind = std::string("/") + shapeName(shape);
    auto add = [&](const std::string& operation, auto function) {
        benchmark::RegisterBenchmark((operation + kind).c_str(), function)
            ->ArgsProduct({sizes()})
            ->Unit(benchmark::kMillisecond);
    };
    auto joints = [](const benchmark::State& state) { return static_cast<unsigned>(state.range(0)); };

    add("read", [=](benchmark::State& state) {
        const std::string& text = actorText(shape, joints(state));
        measure(state, [&] { return &text; }, [](const std::string* t) {
            auto result = std::make_unique<ActorReadResult>(readText(*t));
            if (!*result) result.reset();
            return result;
        });
    });
    add("build", [=](benchmark::State& state) {
        const ActorReadResult read = readText(actorText(shape, joints(state)));
        measure(state, [&] { return &read; }, [](const ActorReadResult* r) {
            return createActorNode(r->document, r->definition, "large.actor", nullptr).actor;
        });
    });
    add("load_osgDB", [=](benchmark::State& state) {
        const std::string path = actorFile(shape, joints(state));
        measure(state, [&] { return &path; }, [](const std::string* p) { return loadActor(*p); });
    });
    add("optimize_osgUtil", [=](benchmark::State& state) {
        const std::string path = actorFile(shape, joints(state));
        measure(state,
                [&] {
                    osg::ref_ptr<osg::Group> scene = new osg::Group;
                    scene->addChild(loadActor(path).get());
                    return scene;
                },
                [](const osg::ref_ptr<osg::Group>& scene) {
                    osgUtil::Optimizer().optimize(scene.get());
                    return scene;
                });
    });
    add("write_osgDB", [=](benchmark::State& state) {
        const std::string path = actorFile(shape, joints(state));
        osgDB::ReaderWriter* writer = osgDB::Registry::instance()->getReaderWriterForExtension("actor");
        measure(state, [&] { return loadActor(path); },
                [writer](const osg::ref_ptr<ActorNode>& actor) {
                    auto out = std::make_unique<std::ostringstream>();
                    if (!actor || !writer->writeNode(*actor, *out).success()) out.reset();
                    return out;
                });
    });
    add("first_frame", [=](benchmark::State& state) {
        const std::string path = actorFile(shape, joints(state));
        measure(state, [&] { return loadActor(path); }, [](const osg::ref_ptr<ActorNode>& actor) {
            auto loop = std::make_unique<FrameLoop>(actor.get(), true);
            loop->frame();
            return loop;
        });
    });
}

void registerMocapBenchmarks()
{
    auto frames = [](const benchmark::State& state) { return static_cast<unsigned>(state.range(0)); };
    benchmark::RegisterBenchmark("read_bvh/frames", [=](benchmark::State& state) {
        const std::string text = longBvhText(frames(state));
        measure(state, [&] { return &text; }, [](const std::string* t) {
            std::istringstream in(*t);
            auto result = std::make_unique<MocapImport>(readBvh(in, "long.bvh"));
            if (!*result) result.reset();
            return result;
        });
    })->ArgsProduct({sizes()})->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark("read_amc/frames", [=](benchmark::State& state) {
        std::istringstream asf(amcSkeletonText());
        const AsfImport skeleton = readAsf(asf, "11.asf");
        const std::string text = longAmcText(frames(state));
        measure(state, [&] { return &text; }, [&](const std::string* t) {
            std::istringstream in(*t);
            auto result = std::make_unique<MocapImport>(readAmc(in, "long.amc", skeleton));
            if (!*result) result.reset();
            return result;
        });
    })->ArgsProduct({sizes()})->Unit(benchmark::kMillisecond);
}

} // namespace

int main(int argc, char** argv)
{
    warmHeap(); // the allocator's settings, before the inputs are made
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
    osgDB::Registry* registry = osgDB::Registry::instance();
    if (osgDB::findLibraryFile(registry->createLibraryNameForExtension("actor")).empty())
    {
        std::fprintf(stderr, "osgactor_scale_bench: osgDB finds no osgdb_actor plugin: run with "
                             "OSG_LIBRARY_PATH=build/lib\n");
        return 1;
    }
    registerActorBenchmarks(SkeletonShape::Wide);
    registerActorBenchmarks(SkeletonShape::Deep);
    registerMocapBenchmarks();
    ScaleReport report;
    benchmark::RunSpecifiedBenchmarks(&report);
    report.printSummary();
    benchmark::Shutdown();
    return 0;
}
