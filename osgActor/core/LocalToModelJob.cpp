// The second step of forward kinematics. Compiled with -O3 and built twice (AVX2+FMA and the x86-64 baseline, see
// detail/HotPath.h), like the first.
#include <osgActor/core/LocalToModelJob>

#include "detail/AffineColumns.h"
#include "detail/ByteFlags.h"
#include "detail/HotPath.h"

#include <cstring>

namespace osgActor {

namespace {

/** Every joint, parents first. Joint after joint down a chain (the parent the joint just before), the parent's
  * columns are still in registers: reading them back from the store just made would add the store-to-load latency
  * to every link of the chain, which is what bounds this loop. */
OSGACTOR_HOT_PATH void composeEveryJoint(const int* parents, const double* const* local, glm::dmat4* model,
                                         unsigned numJoints)
{
    AffineColumns previous{};
    for (unsigned j = 0; j < numJoints; ++j)
    {
        const int parent = parents[j];
        if (parent < 0)
            previous = loadAffine(local[j]);
        else if (parent + 1 == static_cast<int>(j))
            previous = multiplyAffineColumns(previous, local[j]);
        else
            previous = multiplyAffineColumns(loadAffine(&model[parent][0][0]), local[j]);
        storeAffine(&model[j][0][0], previous);
    }
}

/** The joints whose local matrix or an ancestor's changed. A stale parent makes its children stale as the pass
  * reaches them (parents come first, so the parent's flag is final by then); the flags are cleared after. */
OSGACTOR_HOT_PATH void composeStaleJoints(const int* parents, const double* const* local, std::uint8_t* modelStale,
                                          glm::dmat4* model, unsigned numJoints)
{
    for (unsigned j = 0; j < numJoints; ++j)
    {
        const int parent = parents[j];
        if (!modelStale[j])
        {
            if (parent < 0 || !modelStale[parent]) continue;
            modelStale[j] = 1;
        }
        if (parent >= 0)
            multiplyAffineInto(&model[parent][0][0], local[j], &model[j][0][0]);
        else
            std::memcpy(&model[j][0][0], local[j], sizeof(glm::dmat4));
    }
    std::memset(modelStale, 0, numJoints);
}

} // namespace

glm::dmat4 multiplyAffine(const glm::dmat4& a, const glm::dmat4& b)
{
    glm::dmat4 result;
    multiplyAffineInto(&a[0][0], &b[0][0], &result[0][0]);
    return result;
}

bool LocalToModelJob::validate() const
{
    const std::size_t numJoints = parents.size();
    if (local.size() != numJoints || model.size() != numJoints) return false;
    if (!modelStale.empty() && modelStale.size() != numJoints) return false;
    for (std::size_t j = 0; j < numJoints; ++j)
        if (parents[j] < -1 || parents[j] >= static_cast<long>(j)) return false;
    return true;
}

bool LocalToModelJob::run() const
{
    if (!validate()) return false;
    const unsigned numJoints = static_cast<unsigned>(parents.size());
    if (modelStale.empty() || allFlagsSet(modelStale.data(), numJoints))
    {
        composeEveryJoint(parents.data(), local.data(), model.data(), numJoints);
        if (!modelStale.empty()) std::memset(modelStale.data(), 0, numJoints);
        return true;
    }
    composeStaleJoints(parents.data(), local.data(), modelStale.data(), model.data(), numJoints);
    return true;
}

} // namespace osgActor
