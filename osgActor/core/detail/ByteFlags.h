// Internal to the library (not installed, NOT API): tests over arrays of per-joint byte flags (a pose's dirty and
// stale flags), eight flags a word.
#ifndef OSGACTOR_CORE_DETAIL_BYTEFLAGS_H
#define OSGACTOR_CORE_DETAIL_BYTEFLAGS_H 1

#include "Column.h"

#include <cstdint>
#include <cstring>

namespace osgActor {

/** Whether every one of count flags is non-zero, eight at a time: a word w has a zero byte exactly when
  * (w - 0x0101...01) & ~w & 0x8080...80 is non-zero. The last word overlaps the one before rather than leaving a
  * tail of single bytes, which a skeleton's few dozen flags would make a large share of the loop. */
OSGACTOR_INLINE bool allFlagsSet(const std::uint8_t* flags, unsigned count)
{
    constexpr std::uint64_t kLowBits = 0x0101010101010101ull, kHighBits = 0x8080808080808080ull;
    // The high bits of (w - 0x01..01) & ~w, OR-ed over the words, are tested once at the end.
    const auto zeroByteBits = [&](unsigned at) OSGACTOR_INLINE_LAMBDA {
        std::uint64_t word;
        std::memcpy(&word, flags + at, sizeof word);
        return (word - kLowBits) & ~word;
    };
    if (count < 8)
    {
        for (unsigned i = 0; i < count; ++i)
            if (flags[i] == 0) return false;
        return true;
    }
    std::uint64_t zeroBytes = zeroByteBits(count - 8);
    for (unsigned at = 0; at + 8 < count; at += 8) zeroBytes |= zeroByteBits(at);
    return (zeroBytes & kHighBits) == 0;
}

} // namespace osgActor

#endif
