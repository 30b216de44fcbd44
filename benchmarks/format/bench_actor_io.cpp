// Reading and writing the project's humanoid (18 joints, 26 shapes): text to document and definition, document to
// text, and text to a posed ActorNode with its geometry (what osgdb_actor does for each file it loads).
#include <osgActor/ActorSceneIO>
#include <osgActor/io/ActorReader>
#include <osgActor/io/ActorWriter>

#include <benchmark/benchmark.h>

#include <fstream>
#include <sstream>

namespace {

const std::string& humanoidText()
{
    static const std::string text = [] {
        std::ifstream in(std::string(OSGACTOR_BENCH_DATA_DIR) + "/humanoid.actor");
        std::ostringstream out;
        out << in.rdbuf();
        return out.str();
    }();
    return text;
}

void BM_ReadActorText(benchmark::State& state)
{
    const std::string& text = humanoidText();
    for (auto _ : state)
    {
        std::istringstream in(text);
        osgActor::ActorReadResult result = osgActor::readActor(in, "humanoid.actor");
        if (!result) state.SkipWithError(result.error.c_str());
        benchmark::DoNotOptimize(result.definition);
    }
    state.SetBytesProcessed(static_cast<int64_t>(state.iterations() * text.size()));
}
BENCHMARK(BM_ReadActorText);

void BM_WriteActorText(benchmark::State& state)
{
    std::istringstream in(humanoidText());
    const osgActor::ActorReadResult read = osgActor::readActor(in, "humanoid.actor");
    for (auto _ : state)
    {
        std::ostringstream out;
        osgActor::writeActor(out, read.document);
        benchmark::DoNotOptimize(out.str().size());
    }
}
BENCHMARK(BM_WriteActorText);

void BM_CreateActorNode(benchmark::State& state)
{
    std::istringstream in(humanoidText());
    const osgActor::ActorReadResult read = osgActor::readActor(in, "humanoid.actor");
    for (auto _ : state)
    {
        osgActor::ActorNodeResult built = osgActor::createActorNode(read.document, read.definition, "humanoid.actor",
                                                                    nullptr);
        if (!built.actor) state.SkipWithError(built.error.c_str());
        benchmark::DoNotOptimize(built.actor.get());
    }
}
BENCHMARK(BM_CreateActorNode);

} // namespace

BENCHMARK_MAIN();
