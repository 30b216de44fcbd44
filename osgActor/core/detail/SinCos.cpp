// Sine and cosine of a batch of angles, four at a time (sinCosColumn): one range reduction serves both, with no
// branch. Built with -fno-trapping-math but never -ffast-math: the reduction depends on the order of its operations.
#include <osgActor/core/detail/SinCos>

#include "HotPath.h"
#include "SinCosColumn.h"

namespace osgActor {

OSGACTOR_HOT_PATH void sinCos(const double* angles, double* sines, double* cosines, unsigned count)
{
    unsigned i = 0;
    for (; i + 4 <= count; i += 4)
    {
        Column s, c;
        sinCosColumn(loadColumn(angles + i), s, c);
        storeColumn(sines + i, s);
        storeColumn(cosines + i, c);
    }
    if (i == count) return;
    // The last one to three angles, in a column padded with zeros.
    double tail[4] = {0.0, 0.0, 0.0, 0.0}, tailSines[4], tailCosines[4];
    for (unsigned k = 0; i + k < count; ++k) tail[k] = angles[i + k];
    Column s, c;
    sinCosColumn(loadColumn(tail), s, c);
    storeColumn(tailSines, s);
    storeColumn(tailCosines, c);
    for (unsigned k = 0; i + k < count; ++k)
    {
        sines[i + k] = tailSines[k];
        cosines[i + k] = tailCosines[k];
    }
}

} // namespace osgActor
