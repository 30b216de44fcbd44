#include "ScaleReport"

#include <algorithm>
#include <cstdio>
#include <set>
#include <string>

namespace bench {

double ScaleReport::Measure::medianSeconds() const
{
    if (seconds.empty()) return 0.0;
    std::vector<double> sorted = seconds;
    std::sort(sorted.begin(), sorted.end());
    const std::size_t middle = sorted.size() / 2;
    return sorted.size() % 2 ? sorted[middle] : 0.5 * (sorted[middle - 1] + sorted[middle]);
}

ScaleReport::Measure& ScaleReport::measureOf(const std::string& row, long size)
{
    auto it = std::find_if(_rows.begin(), _rows.end(), [&row](const auto& entry) { return entry.first == row; });
    if (it == _rows.end()) it = _rows.emplace(_rows.end(), row, std::map<long, Measure>());
    return it->second[size];
}

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
        Measure& measure = measureOf(row, size);
        measure.seconds.push_back(run.cpu_accumulated_time / static_cast<double>(run.iterations));
        const auto peak = run.counters.find(kPeakBytesPerItem);
        if (peak != run.counters.end()) measure.peakBytesPerItem = peak->second.value;
        const auto held = run.counters.find(kHeldBytesPerItem);
        if (held != run.counters.end()) measure.heldBytesPerItem = held->second.value;
        const auto allocations = run.counters.find(kAllocationsPerItem);
        if (allocations != run.counters.end()) measure.allocationsPerItem = allocations->second.value;
        const auto faults = run.counters.find(kMinorFaultsPerItem);
        if (faults != run.counters.end()) measure.minorFaultsPerItem = faults->second.value;
    }
}

int ScaleReport::printSummary() const
{
    std::set<long> sizes;
    for (const auto& row : _rows)
        for (const auto& size : row.second) sizes.insert(size.first);
    std::vector<long> tenfold; // sizes whose tenfold is there too
    for (long size : sizes)
        if (sizes.count(size * 10)) tenfold.push_back(size);

    std::printf("\nCPU time (ms) at each size, its growth from a size to ten times it (column x<size>; linear: 10, "
                "target: at most %.0f), the peak resident memory per item (joint or frame; in parentheses, what "
                "the result holds after, at the largest size), the heap allocations per item at the largest size, and "
                "the minor page faults per item and timed run at each size\n%-24s",
                kMaxGrowthPerTenfold, "operation/kind");
    for (long size : sizes) std::printf(" %9ld", size);
    for (long size : tenfold) std::printf(" %9s", ("x" + std::to_string(size)).c_str());
    std::printf("  peak B/item at each size (held)  allocs/item  faults/item at each size\n");

    int over = 0;
    for (const auto& [row, measures] : _rows)
    {
        std::printf("%-24s", row.c_str());
        for (long size : sizes)
        {
            const auto it = measures.find(size);
            if (it == measures.end()) std::printf(" %9s", "-");
            else std::printf(" %9.3f", it->second.medianSeconds() * 1e3);
        }
        for (long size : tenfold)
        {
            const auto small = measures.find(size), large = measures.find(size * 10);
            if (small == measures.end() || large == measures.end() || small->second.medianSeconds() <= 0.0)
            {
                std::printf(" %9s", "-");
                continue;
            }
            const double growth = large->second.medianSeconds() / small->second.medianSeconds();
            if (growth > kMaxGrowthPerTenfold) ++over;
            std::printf(" %8.1f%s", growth, growth > kMaxGrowthPerTenfold ? "!" : " ");
        }
        std::printf(" ");
        for (long size : sizes)
        {
            const auto it = measures.find(size);
            if (it == measures.end()) std::printf(" %6s", "-");
            else std::printf(" %6.0f", it->second.peakBytesPerItem);
        }
        if (!measures.empty() && measures.rbegin()->second.heldBytesPerItem > 0.0)
            std::printf("  (%.0f)", measures.rbegin()->second.heldBytesPerItem);
        if (!measures.empty()) std::printf("  %.1f ", measures.rbegin()->second.allocationsPerItem);
        for (const auto& [size, measure] : measures) std::printf(" %.2f", measure.minorFaultsPerItem);
        std::printf("\n");
    }
    if (over) std::printf("%d growth ratios above %.0f (marked !)\n", over, kMaxGrowthPerTenfold);
    return over;
}

} // namespace bench
