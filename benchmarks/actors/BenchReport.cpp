#include "BenchReport"
#include "PeerScenes"

#include <malloc.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <map>
#include <tuple>

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
        // With --benchmark_repetitions the summary takes each benchmark's median; the repetitions themselves (and
        // the other aggregates) only go to the console.
        if (run.repetitions > 1 && (run.run_type != Run::RT_Aggregate || run.aggregate_name != "median")) continue;
        // Names look like "update/osgActor_all/1000", perhaps followed by "/real_time" or "/iterations:1".
        std::vector<std::string> parts;
        const std::string name = run.run_name.str();
        for (std::size_t start = 0, slash; start <= name.size(); start = slash + 1)
        {
            slash = name.find('/', start);
            if (slash == std::string::npos) slash = name.size();
            parts.push_back(name.substr(start, slash - start));
        }
        if (parts.size() < 3) continue;
        Result result{parts[0], parts[1], std::atol(parts[2].c_str()), 0.0};
        // ns_per_joint is an inverted rate, so Google Benchmark reports it in seconds per joint.
        const auto perJoint = run.counters.find("ns_per_joint");
        if (perJoint != run.counters.end()) result.value = perJoint->second * 1e9;
        const auto bytes = run.counters.find("bytes_per_actor");
        if (bytes != run.counters.end()) result.value = bytes->second;
        _results.push_back(result);
    }
}

namespace {

/** Where a row goes in the summary: by mode, then N, then system, whatever order the runs came in (random
  * interleaving shuffles them). */
int rank(const std::string& name, std::initializer_list<const char*> order)
{
    int i = 0;
    for (const char* known : order)
    {
        if (name == known) return i;
        ++i;
    }
    return i;
}

} // namespace

void SummaryReporter::writeSummary()
{
    std::stable_sort(_results.begin(), _results.end(), [](const Result& a, const Result& b) {
        const auto key = [](const Result& r) {
            return std::make_tuple(rank(r.mode, {"update", "update_cull", "update_cull_nearfar", "frame_in_view", "frame_quarter_in_view",
                                                 "parallel", "parallel_cull", "parallel_cull_instanced", "memory"}),
                                   r.n,
                                   rank(r.system, {"osgActor_all", "osgActor_all_nodebynode", "osgActor_all_follow",
                                                   "osgActor_quarter", "osgActor_idle", "osgActor_all_instanced",
                                                   "osgActor_quarter_instanced", "osgActor_idle_instanced",
                                                   "osgAnimation", "plainOSG",
                                                   "osgActor_1thread", "osgActor_2threads", "osgActor_4threads",
                                                   "osgActor_8threads", "osgActor_16threads"}),
                                   r.system);
        };
        return key(a) < key(b);
    });
    // The reference of each row: osgAnimation at the same mode and N; for the parallel rows, one thread.
    std::map<std::pair<std::string, long>, double> osgAnimation;
    for (const Result& r : _results)
        if (r.system == "osgAnimation" || r.system == "osgActor_1thread") osgAnimation[{r.mode, r.n}] = r.value;

    const std::string dir = outputDirectory();
    std::error_code error;
    std::filesystem::create_directories(dir, error); // OSGACTOR_BENCH_OUT may name a folder not made yet
    const std::string csvPath = dir + "/osgactor_bench.csv";
    std::ofstream csv(csvPath);
    csv << "mode,system,n,value,unit,ratio_to_osgAnimation\n";
    std::printf("\n%-12s %-18s %6s %14s %s\n", "mode", "system", "N", "value", "vs osgAnimation");
    for (const Result& r : _results)
    {
        const auto it = osgAnimation.find({r.mode, r.n});
        const double ratio = it != osgAnimation.end() && r.value > 0.0 ? it->second / r.value : 0.0;
        const char* unit = r.mode == "memory" ? "bytes/actor" : "ns/joint";
        csv << r.mode << ',' << r.system << ',' << r.n << ',' << r.value << ',' << unit << ',' << ratio << '\n';
        if (ratio > 0.0 && (r.mode == "parallel" || r.mode == "parallel_cull" || r.mode == "parallel_cull_instanced"))
            std::printf("%-12s %-18s %6ld %9.1f %-11s %.2fx the speed of one thread\n", r.mode.c_str(),
                        r.system.c_str(), r.n, r.value, unit, ratio);
        else if (ratio > 0.0 && r.mode != "memory")
            std::printf("%-12s %-18s %6ld %9.1f %-11s %.1fx faster\n", r.mode.c_str(), r.system.c_str(), r.n,
                        r.value, unit, ratio);
        else if (ratio > 0.0)
            std::printf("%-12s %-18s %6ld %9.0f %-11s %.1fx less\n", r.mode.c_str(), r.system.c_str(), r.n, r.value,
                        unit, ratio);
        else
            std::printf("%-12s %-18s %6ld %9.2f %s\n", r.mode.c_str(), r.system.c_str(), r.n, r.value, unit);
    }
    // Each system's whole frame with every instance in view against its frame with three in four out of view.
    std::map<std::pair<std::string, long>, double> inView;
    for (const Result& r : _results)
        if (r.mode == "frame_in_view") inView[{r.system, r.n}] = r.value;
    for (const Result& r : _results)
    {
        const auto it = inView.find({r.system, r.n});
        if (r.mode != "frame_quarter_in_view" || it == inView.end() || r.value <= 0.0) continue;
        const double gain = it->second / r.value;
        csv << "out_of_view_gain," << r.system << ',' << r.n << ',' << gain << ",x,0\n";
        std::printf("%-12s %-18s %6ld %9.2fx cheaper with 3 in 4 out of view\n", "frame", r.system.c_str(), r.n,
                    gain);
    }
    csv.close();
    if (!csv)
    {
        std::printf("\nresults: could not write %s\n", csvPath.c_str());
        return;
    }
    std::printf("\nresults: %s\n", csvPath.c_str());

    // The plot: ns per joint against N for each system, update and update+cull side by side, log scales. gnuplot
    // reads one block per curve (blocks separated by two blank lines), so the points of a curve are joined.
    const std::string plotPath = dir + "/osgactor_bench.png";
    const std::string dataPath = dir + "/osgactor_bench_plot.dat";
    const std::string script = dir + "/osgactor_bench.gp";
    std::ofstream data(dataPath);
    std::ofstream gp(script);
    gp << "set terminal pngcairo size 1100,520 font 'sans,10' noenhanced\n"
          "set output '" << plotPath << "'\n"
          "set logscale xy\nset grid\nset key below\nset xrange [0.7:20000]\nset yrange [0.5:5000]\n"
          "set xlabel 'actors (31 joints each)'\nset ylabel 'ns per joint'\n"
          "set multiplot layout 1,2\n";
    int block = 0;
    for (const char* mode : {"update", "update_cull"})
    {
        gp << "set title '" << mode << "'\nplot ";
        bool first = true;
        for (const char* system : {"osgActor_all", "osgActor_all_nodebynode", "osgActor_all_follow", "osgActor_quarter",
                                   "osgActor_idle", "osgAnimation", "plainOSG"})
        {
            // A system without results in this mode (the node-by-node cull has no update of its own) gets no block:
            // gnuplot does not count an empty one, and the curves after it would take the wrong blocks.
            bool any = false;
            for (const Result& r : _results) any = any || (r.mode == mode && r.system == system);
            if (!any) continue;
            data << "# " << mode << " " << system << "\n";
            for (const Result& r : _results)
                if (r.mode == mode && r.system == system) data << r.n << ' ' << r.value << '\n';
            data << "\n\n";
            gp << (first ? "" : ", ") << "'" << dataPath << "' index " << block++
               << " using 1:2 with linespoints title '" << system << "'";
            first = false;
        }
        gp << "\n";
    }
    gp << "unset multiplot\n";
    gp.close();
    data.close();
    const std::string command = "gnuplot '" + script + "' 2>/dev/null";
    if (std::system("command -v gnuplot >/dev/null 2>&1") != 0)
        std::printf("plot: not written (gnuplot not installed; scripts/setup-debian.sh installs gnuplot-nox)\n");
    else if (std::system(command.c_str()) != 0)
        std::printf("plot: not written (gnuplot failed on %s)\n", script.c_str());
    else
        std::printf("plot: %s\n", plotPath.c_str());
}

} // namespace bench
