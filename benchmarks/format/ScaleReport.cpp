#include "ScaleReport"

#include <cstdio>

namespace bench {

void ScaleReport::ReportRuns(const std::vector<Run>& runs)
{
    benchmark::ConsoleReporter::ReportRuns(runs);
    for (const Run& run : runs)
    {
        if (run.error_occurred || run.run_type != Run::RT_Iteration || run.iterations == 0) continue;
        const std::string name = run.benchmark_name();
        const std::size_t slash = name.rfind('/');
        if (slash == std::string::npos) continue;
        const std::string row = name.substr(0, slash);
        const long size = std::stol(name.substr(slash + 1));
        if (_rows.empty() || _rows.back().first != row) _rows.emplace_back(row, std::map<long, Measure>());
        Measure& measure = _rows.back().second[size];
        measure.seconds = run.real_accumulated_time / static_cast<double>(run.iterations);
        const auto peak = run.counters.find(kPeakBytesPerItem);
        if (peak != run.counters.end()) measure.peakBytesPerItem = peak->second.value;
        const auto held = run.counters.find(kHeldBytesPerItem);
        if (held != run.counters.end()) measure.heldBytesPerItem = held->second.value;
    }
}

int ScaleReport::printSummary() const
{
    int over = 0;
    std::printf("\nTime at each size, growth per tenfold size (linear: 10, target: at most %.0f), and peak resident "
                "memory per item (joint or frame)\n",
                kMaxGrowthPerTenfold);
    std::printf("%-26s %10s %10s %10s %8s %8s   %s\n", "operation/kind", "1e3 (ms)", "1e4 (ms)", "1e5 (ms)",
                "x 1e3>4", "x 1e4>5", "peak B/item at 1e3 1e4 1e5 (held after, at 1e5)");
    for (const auto& [row, sizes] : _rows)
    {
        std::printf("%-26s", row.c_str());
        for (long size : {1000L, 10000L, 100000L})
        {
            const auto it = sizes.find(size);
            if (it == sizes.end()) std::printf(" %10s", "-");
            else std::printf(" %10.3f", it->second.seconds * 1e3);
        }
        for (long size : {1000L, 10000L})
        {
            const auto small = sizes.find(size), large = sizes.find(size * 10);
            if (small == sizes.end() || large == sizes.end() || small->second.seconds <= 0.0)
            {
                std::printf(" %8s", "-");
                continue;
            }
            const double growth = large->second.seconds / small->second.seconds;
            if (growth > kMaxGrowthPerTenfold) ++over;
            std::printf(" %7.1f%s", growth, growth > kMaxGrowthPerTenfold ? "!" : " ");
        }
        std::printf("  ");
        for (long size : {1000L, 10000L, 100000L})
        {
            const auto it = sizes.find(size);
            if (it == sizes.end()) std::printf(" %6s", "-");
            else std::printf(" %6.0f", it->second.peakBytesPerItem);
        }
        const auto largest = sizes.find(100000L);
        if (largest != sizes.end() && largest->second.heldBytesPerItem > 0.0)
            std::printf("  (%.0f)", largest->second.heldBytesPerItem);
        std::printf("\n");
    }
    if (over) std::printf("%d growth ratios above %.0f (marked !)\n", over, kMaxGrowthPerTenfold);
    return over;
}

} // namespace bench
