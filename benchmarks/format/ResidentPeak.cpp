#include "ResidentPeak"

#include <malloc.h>

#include <fstream>
#include <string>

namespace bench {

namespace {

/** A "VmRSS:" or "VmHWM:" line of /proc/self/status, in bytes; 0 if there is none. */
std::size_t statusBytes(const std::string& key)
{
    std::ifstream status("/proc/self/status");
    for (std::string name; status >> name;)
    {
        std::size_t kilobytes = 0;
        if (name == key && status >> kilobytes) return kilobytes * 1024;
        status.ignore(1 << 16, '\n');
    }
    return 0;
}

} // namespace

ResidentPeak::ResidentPeak()
{
    malloc_trim(0);
    std::ofstream clearRefs("/proc/self/clear_refs");
    _valid = static_cast<bool>(clearRefs << "5" << std::flush);
    _baseline = statusBytes("VmRSS:");
}

std::size_t ResidentPeak::peakBytes() const
{
    const std::size_t peak = statusBytes("VmHWM:");
    return _valid && peak > _baseline ? peak - _baseline : 0;
}

std::size_t ResidentPeak::heldBytes() const
{
    const std::size_t now = statusBytes("VmRSS:");
    return _valid && now > _baseline ? now - _baseline : 0;
}

} // namespace bench
