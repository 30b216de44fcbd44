// Internal to the library (not installed): the largest of a run of indices, for the skin jobs' validate(), which scan
// every index they will read each run.
#ifndef OSGACTOR_CORE_SKIN_INDEXSCAN_H
#define OSGACTOR_CORE_SKIN_INDEXSCAN_H 1

#include "Float4.h" // OSGACTOR_SKIN_INLINE

#include <cstddef>

namespace osgActor {
namespace skin {

/** The largest element of a run of indices, or -1 for none: a plain loop the compiler vectorises (the baseline has
  * no unsigned 16- or 32-bit maximum instruction, x86-64-v3 has both), so call it from an OSGACTOR_HOT_PATH
  * function: validate() scans every index each run, so this is on the hot path too. */
template <class Index>
OSGACTOR_SKIN_INLINE long long largestIndexOf(const Index* __restrict indices, std::size_t count)
{
    Index largest = 0;
    for (std::size_t i = 0; i < count; ++i) largest = indices[i] > largest ? indices[i] : largest;
    return count == 0 ? -1 : static_cast<long long>(largest);
}

} // namespace skin
} // namespace osgActor

#endif
