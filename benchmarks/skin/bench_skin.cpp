// CPU skinning (issue 26): SkinningJob in vertices per second on one core, per configuration, and ozz-animation's
// SkinningJob beside it where it was found at configure time; then the per-frame jobs around it (skinning matrices,
// bounds). Figures go to docs/performance.md.
#include "SkinBenchMesh"

#include <osgActor/core/skin/SkinBoundsJob>
#include <osgActor/core/skin/SkinningJob>

#include <benchmark/benchmark.h>

#include <cstdio>
#include <map>
#include <string>

namespace bench {

const std::vector<SkinBenchCase>& skinBenchCases()
{
    using osgActor::SkinningMethod;
    static const std::vector<SkinBenchCase> cases{
        {"lbs_k1_pn", 1, true, false, SkinningMethod::LinearBlend, false},
        {"lbs_k2_pn", 2, true, false, SkinningMethod::LinearBlend, false},
        {"lbs_k4_pn", 4, true, false, SkinningMethod::LinearBlend, false},
        {"lbs_k8_pn", 8, true, false, SkinningMethod::LinearBlend, false},
        {"lbs_k4_p", 4, false, false, SkinningMethod::LinearBlend, false},
        {"lbs_k4_pnt", 4, true, true, SkinningMethod::LinearBlend, false},
        {"lbs_k4_pn_inverse_transpose", 4, true, false, SkinningMethod::LinearBlend, true},
        {"dq_k4_p", 4, false, false, SkinningMethod::DualQuaternion, false},
        {"dq_k4_pn", 4, true, false, SkinningMethod::DualQuaternion, false},
        {"dq_k4_pnt", 4, true, true, SkinningMethod::DualQuaternion, false},
    };
    return cases;
}

const std::vector<unsigned>& skinBenchSizes()
{
    static const std::vector<unsigned> sizes{16384, 262144};
    return sizes;
}

} // namespace bench

namespace {

void BM_SkinningJob(benchmark::State& state, bench::SkinBenchCase config)
{
    const unsigned numVertices = static_cast<unsigned>(state.range(0));
    const osgActor::SkinPtr skin = bench::makeSkin(numVertices, config.influences, config.method);
    const bench::SkinBenchPose pose;
    std::vector<glm::vec3> positions(numVertices), normals(numVertices);
    std::vector<glm::vec4> tangents(numVertices);
    osgActor::SkinningJob job;
    job.method = config.method;
    job.vertices = skin->getVertices();
    job.matrices = pose.matrices;
    if (config.inverseTranspose) job.normalMatrices = pose.normalMatrices;
    job.dualQuaternions = pose.dualQuaternions;
    job.bindScale = static_cast<float>(skin->getBindScale());
    job.positions = positions;
    if (config.normals) job.normals = normals;
    if (config.tangents) job.tangents = tangents;
    if (!job.validate()) state.SkipWithError("invalid job");
    for (auto _ : state)
    {
        job.run();
        benchmark::ClobberMemory();
    }
    state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * numVertices);
}

/** The skinning matrices of a 64-joint skin from its pose (double product, float, inverse transposes, dual
  * quaternions): once per frame per skin. */
void BM_SkinningMatricesJob(benchmark::State& state)
{
    bench::SkinBenchPose pose;
    osgActor::SkinningMatricesJob job;
    job.modelMatrices = pose.model;
    job.definitionJoints = pose.definitionJoints;
    job.inverseBindMatrices = pose.inverseBinds;
    job.matrices = pose.matrices;
    if (state.range(0) != 0)
    {
        job.normalMatrices = pose.normalMatrices;
        job.dualQuaternions = pose.dualQuaternions;
    }
    for (auto _ : state)
    {
        job.run();
        benchmark::ClobberMemory();
    }
    state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * bench::kSkinJoints);
}

/** The bound of a 64-joint, 16384-vertex skin with 4 influences (its pieces moved): once per frame per skin. Argument:
  * 0 linear blend, 1 dual quaternions, 2 linear blend with every piece moved one at a time (the skin's groups left
  * out: the path dual quaternions and pieces of more than four joints take), the peer of 0. */
void BM_SkinBoundsJob(benchmark::State& state)
{
    const osgActor::SkinningMethod method =
        state.range(0) == 1 ? osgActor::SkinningMethod::DualQuaternion : osgActor::SkinningMethod::LinearBlend;
    const osgActor::SkinPtr skin = bench::makeSkin(16384, 4, method);
    const bench::SkinBenchPose pose;
    osgActor::SkinBox bound;
    osgActor::SkinBoundsJob job = osgActor::makeSkinBoundsJob(*skin);
    if (state.range(0) == 2) job.blendSetGroups = osgActor::Span<const osgActor::SkinBlendSetGroup>();
    job.matrices = pose.matrices;
    job.bound = &bound;
    for (auto _ : state)
    {
        job.run();
        benchmark::DoNotOptimize(bound);
    }
    state.counters["pieces"] = static_cast<double>(skin->getBlendSets().size());
    // The groups the job moves (linear blend only).
    state.counters["groups"] =
        method == osgActor::SkinningMethod::LinearBlend ? static_cast<double>(job.blendSetGroups.size()) : 0.0;
}

/** The console output, then per configuration and size osgActor's vertices per second and, where ozz ran, ozz's
  * and osgActor's over ozz's (above 1: osgActor faster). With --benchmark_repetitions, the medians. */
class RateReporter : public benchmark::ConsoleReporter
{
public:
    void ReportRuns(const std::vector<Run>& runs) override
    {
        ConsoleReporter::ReportRuns(runs);
        for (const Run& run : runs)
        {
            const bool aggregate = run.run_type == Run::RT_Aggregate;
            if ((aggregate && run.aggregate_name != "median") || run.error_occurred) continue;
            const auto rate = run.counters.find("items_per_second");
            if (rate == run.counters.end()) continue;
            _rates[run.run_name.function_name + "/" + run.run_name.args] = rate->second.value;
        }
    }
    void printSummary() const
    {
        std::printf("\nvertices per second on one core (millions):\n");
        for (const bench::SkinBenchCase& config : bench::skinBenchCases())
            for (const unsigned size : bench::skinBenchSizes())
            {
                const std::string key = std::string(config.name) + "/" + std::to_string(size);
                const auto ours = _rates.find("skin/osgActor/" + key);
                if (ours == _rates.end()) continue;
                std::printf("  %-30s %7u vertices  osgActor %7.1f", config.name, size, ours->second / 1e6);
                const auto ozz = _rates.find("skin/ozz/" + key);
                if (ozz != _rates.end())
                    std::printf("  ozz %7.1f  osgActor/ozz %.2f", ozz->second / 1e6, ours->second / ozz->second);
                std::printf("\n");
            }
#if !OSGACTOR_SKIN_BENCH_WITH_OZZ
        std::printf("  ozz-animation: absent (not found at configure time; see docs/performance.md)\n");
#endif
    }

private:
    std::map<std::string, double> _rates;
};

} // namespace

int main(int argc, char** argv)
{
    benchmark::Initialize(&argc, argv);
    for (const bench::SkinBenchCase& config : bench::skinBenchCases())
        for (const unsigned size : bench::skinBenchSizes())
            benchmark::RegisterBenchmark((std::string("skin/osgActor/") + config.name).c_str(), BM_SkinningJob, config)
                ->Arg(size);
#if OSGACTOR_SKIN_BENCH_WITH_OZZ
    bench::registerOzzSkinning();
#endif
    benchmark::RegisterBenchmark("frame/skinning_matrices", BM_SkinningMatricesJob)->Arg(0)->Arg(1);
    benchmark::RegisterBenchmark("frame/bounds", BM_SkinBoundsJob)->Arg(0)->Arg(2)->Arg(1);
    RateReporter reporter;
    benchmark::RunSpecifiedBenchmarks(&reporter);
    reporter.printSummary();
    benchmark::Shutdown();
    return 0;
}
