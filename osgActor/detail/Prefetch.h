// Internal to the library (not installed, NOT API): asking the processor to fetch memory a per-frame loop will read
// soon, so the fetch overlaps work done before it. A hint: where the compiler has no such builtin it does nothing.
#ifndef OSGACTOR_DETAIL_PREFETCH_H
#define OSGACTOR_DETAIL_PREFETCH_H 1

#include <cstddef>

namespace osgActor {
namespace detail {

/** Every cache line of [begin, begin + bytes), for reading, into L2 (locality 2), as the skeleton-node prefetch. */
inline void prefetchForRead(const void* begin, std::size_t bytes)
{
#if defined(__GNUC__)
    const char* const first = static_cast<const char*>(begin);
    for (std::size_t offset = 0; offset < bytes; offset += 64) __builtin_prefetch(first + offset, 0, 2);
    if (bytes > 0) __builtin_prefetch(first + bytes - 1, 0, 2);
#else
    (void)begin;
    (void)bytes;
#endif
}

/** The one cache line that holds address, into L2: for reading or, ForWrite, to be written (a reference count, an
  * object reused). */
template <bool ForWrite = false>
inline void prefetchLine(const void* address)
{
#if defined(__GNUC__)
    __builtin_prefetch(address, ForWrite ? 1 : 0, 2);
#else
    (void)address;
#endif
}

} // namespace detail
} // namespace osgActor

#endif
