#include "BenchReport"
#include "PeerScenes"

#include <malloc.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>

namespace bench {

namespace {

std::size_t heapInUse() { return mallinfo2().uordblks; }

void measureMemory(benchmark::State& state, int system)
{
    const unsigned n = static_cast<unsigned>(state.range(0));
    // Build one scene first so one-time costs (shared clip data, the shared geode) are not counted.
    osg::ref_ptr<osg::Group> warm = system == 0   ? makeOsgActorScene(1, Motion::All)
                                    : system == 1 ? makeOsgAnimationScene(1)
                                                  : makePlainOsgScene(1);
    double perInstance = 0.0;
    for (auto _ : state)
    {
        const std::size_t before = heapInUse();
        osg::ref_ptr<osg::Group> scene = system == 0   ? makeOsgActorScene(n, Motion::All)
                                         : system == 1 ? makeOsgAnimationScene(n)
                                                       : makePlainOsgScene(n);
        perInstance = static_cast<double>(heapInUse() - before) / n;
        benchmark::DoNotOptimize(scene.get());
    }
    state.counters["bytes_per_actor"] = perInstance;
}

std::string outputDirectory()
{
    const char* dir = std::getenv("OSGACTOR_BENCH_OUT");
    return dir && *dir ? std::string(dir) : std::string(".");
}

} // namespace

void registerMemoryBenchmarks()
{
    const char* const names[] = {"memory/osgActor_all", "memory/osgAnimation", "memory/plainOSG"};
    for (int s = 0; s < 3; ++s)
        benchmark::RegisterBenchmark(names[s], [s](benchmark::State& state) { measureMemory(state, s); })
            ->Arg(100)->Iterations(1);
}

void SummaryReporter::ReportRuns(const std::vector<Run>& runs)
{
    benchmark::ConsoleReporter::ReportRuns(runs);
    for (const Run& run : runs)
    {
        if (run.error_occurred) continue;
        // Names look like "update/osgActor_all/1000".
        const std::string name = run.benchmark_name();
        const std::size_t a = name.find('/'), b = name.rfind('/');
        if (a == std::string::npos || b == a) continue;
        Result result{name.substr(0, a), name.substr(a + 1, b - a - 1), std::atol(name.c_str() + b + 1), 0.0};
        // ns_per_joint is an inverted rate, so Google Benchmark reports it in seconds per joint.
        const auto perJoint = run.counters.find("ns_per_joint");
        if (perJoint != run.counters.end()) result.value = perJoint->second * 1e9;
        for (const char* counter : {"bytes_per_actor", "speedup"})
        {
            const auto it = run.counters.find(counter);
            if (it != run.counters.end()) result.value = it->second;
        }
        _results.push_back(result);
    }
}

void SummaryReporter::writeSummary() const
{
    std::map<std::pair<std::string, long>, double> osgAnimation;
    for (const Result& r : _results)
        if (r.system == "osgAnimation") osgAnimation[{r.mode, r.n}] = r.value;

    const std::string dir = outputDirectory();
    const std::string csvPath = dir + "/osgactor_bench.csv";
    std::ofstream csv(csvPath);
    csv << "mode,system,n,value,unit,ratio_to_osgAnimation\n";
    std::printf("\n%-12s %-18s %6s %14s %s\n", "mode", "system", "N", "value", "vs osgAnimation");
    for (const Result& r : _results)
    {
        const auto it = osgAnimation.find({r.mode, r.n});
        const double ratio = it != osgAnimation.end() && r.value > 0.0 ? it->second / r.value : 0.0;
        const char* unit = r.mode == "memory" ? "bytes/actor" : r.mode == "parallel" ? "x" : "ns/joint";
        csv << r.mode << ',' << r.system << ',' << r.n << ',' << r.value << ',' << unit << ',' << ratio << '\n';
        if (ratio > 0.0 && r.mode != "memory")
            std::printf("%-12s %-18s %6ld %9.1f %-11s %.1fx faster\n", r.mode.c_str(), r.system.c_str(), r.n,
                        r.value, unit, ratio);
        else if (ratio > 0.0)
            std::printf("%-12s %-18s %6ld %9.0f %-11s %.1fx less\n", r.mode.c_str(), r.system.c_str(), r.n, r.value,
                        unit, ratio);
        else
            std::printf("%-12s %-18s %6ld %9.2f %s\n", r.mode.c_str(), r.system.c_str(), r.n, r.value, unit);
    }
    csv.close();
    std::printf("\nresults: %s\n", csvPath.c_str());

    // The plot: ns per joint against N for each system, update and update+cull side by side, log scales.
    const std::string plotPath = dir + "/osgactor_bench.png";
    const std::string script = dir + "/osgactor_bench.gp";
    std::ofstream gp(script);
    gp << "set terminal pngcairo size 1100,450 font 'sans,10'\n"
          "set output '" << plotPath << "'\n"
          "set datafile separator ','\n"
          "set logscale xy\nset grid\nset key top left\n"
          "set xlabel 'actors (31 joints each)'\nset ylabel 'ns per joint'\n"
          "set multiplot layout 1,2\n";
    for (const char* mode : {"update", "update_cull"})
    {
        gp << "set title '" << mode << "'\nplot ";
        bool first = true;
        for (const char* system : {"osgActor_all", "osgActor_quarter", "osgActor_idle", "osgAnimation", "plainOSG"})
        {
            gp << (first ? "" : ", ") << "'" << csvPath << "' using ($1 eq '" << mode << "' && $2 eq '" << system
               << "' ? $3 : 1/0):4 with linespoints title '" << system << "'";
            first = false;
        }
        gp << "\n";
    }
    gp << "unset multiplot\n";
    gp.close();
    const std::string command = "gnuplot '" + script + "' 2>/dev/null";
    if (std::system("command -v gnuplot >/dev/null 2>&1") == 0 && std::system(command.c_str()) == 0)
        std::printf("plot: %s\n", plotPath.c_str());
    else
        std::printf("plot: not written (gnuplot not installed; scripts/setup-debian.sh installs gnuplot-nox)\n");
}

} // namespace bench
