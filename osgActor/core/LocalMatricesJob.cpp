// The first step of forward kinematics on the per-frame path. This file is compiled with -O3 and its loop is built
// twice (AVX2+FMA and the x86-64 baseline, see detail/HotPath.h), the right one chosen when the library is loaded.
#include <osgActor/core/LocalMatricesJob>

#include "detail/ByteFlags.h"
#include "detail/HotPath.h"
#include "detail/JointMatrixKernel.h"

#include <cstring>

namespace osgActor {

using namespace joint_matrix_detail;

namespace {

/** The job's views as raw pointers, read once: the flags are bytes, which may alias anything, so the job's fields
  * would be reloaded after each flag store. */
struct LocalMatricesBuffers
{
    const ActorDefinition& definition;
    const double* dofs;
    std::uint8_t* jointDirty;
    double* const* local;
    std::uint8_t* localChanged;
    std::uint8_t* modelStale;

    /** The flags of a joint whose local matrix was just rebuilt. */
    OSGACTOR_INLINE void markRebuilt(unsigned joint) const
    {
        jointDirty[joint] = 0;
        localChanged[joint] = 1;
        modelStale[joint] = 1;
    }
};

/** For a pose with an angle beyond the fast sine and cosine's range (more than 1e6 radians): joint by joint, through
  * the library's functions. Returns how many joints it rebuilt. */
unsigned buildExactly(const LocalMatricesBuffers& b)
{
    unsigned numRebuilt = 0;
    for (unsigned joint = 0; joint < b.definition.getNumJoints(); ++joint)
    {
        if (!b.jointDirty[joint]) continue;
        const JointKinematics& k = b.definition.getKinematics(joint);
        buildJointMatrixDispatched(k, b.dofs, TrigInOrder::exact(k, b.dofs), b.local[joint]);
        b.markRebuilt(joint);
        ++numRebuilt;
    }
    return numRebuilt;
}

/** The dirty joints' local matrices, batch by batch (see JointBatch), then the joints built one at a time. A batch
  * with a single dirty joint builds it on its own, which is cheaper than four lanes. Returns how many joints it
  * rebuilt. A pose with an angle beyond the fast sine and cosine's range goes to buildExactly. */
OSGACTOR_HOT_PATH unsigned buildLocalMatrices(const LocalMatricesBuffers b)
{
    const JointBatchPlan& plan = b.definition.getJointBatches();
    const JointKinematics* const kinematics = b.definition.getAllKinematics().data();
    const unsigned numJoints = b.definition.getNumJoints();
    const double* const dofs = b.dofs;
    std::uint8_t* const jointDirty = b.jointDirty;
    double* const* const local = b.local;
    FastSinCosRangeGuard guard;
    const auto buildOne = [&](unsigned joint) OSGACTOR_INLINE_LAMBDA {
        const JointKinematics& k = kinematics[joint];
        buildJointMatrixDispatched(k, dofs, TrigInOrder::inFastRange(k, dofs, guard), local[joint]);
    };
    const auto buildBatch = [&](const JointBatch& batch, unsigned lanes) OSGACTOR_INLINE_LAMBDA {
        withRotationSequence(batch.rotationSequence, [&](auto sequence) OSGACTOR_INLINE_LAMBDA {
            buildBatchMatrices<decltype(sequence)::value>(batch, kinematics, dofs, local, lanes, guard);
        });
    };

    if (allFlagsSet(jointDirty, numJoints))
    {
        // A clip playing moves every joint: no flag to test per joint, and the flags set in three sweeps after. The
        // angles' range is checked as they are gathered; no flag has changed yet if a redo is needed.
        for (const JointBatch& batch : plan.batches) buildBatch(batch, (1u << batch.numJoints) - 1u);
        for (const std::uint32_t joint : plan.singleJoints) buildOne(joint);
        if (!guard.passed()) return buildExactly(b);
        std::memset(jointDirty, 0, numJoints);
        std::memset(b.localChanged, 1, numJoints);
        std::memset(b.modelStale, 1, numJoints);
        return numJoints;
    }

    // Some joints: flags change as joints are built, so the range is checked first, over the whole DOF vector
    // (translations too: cheaper than picking the angles out).
    if (!withinFastSinCosRange(dofs, b.definition.getNumDofs())) return buildExactly(b);
    unsigned numRebuilt = 0;
    for (const JointBatch& batch : plan.batches)
    {
        // Every lane is read, unused ones too (they repeat a joint), and the unused ones masked off after.
        unsigned lanes = 0;
        for (unsigned lane = 0; lane < JointBatch::kWidth; ++lane)
            lanes |= (jointDirty[batch.joints[lane]] != 0 ? 1u : 0u) << lane;
        lanes &= (1u << batch.numJoints) - 1u;
        if (lanes == 0) continue;
        if ((lanes & (lanes - 1)) == 0)
        {
            const unsigned joint = batch.joints[__builtin_ctz(lanes)];
            buildOne(joint);
            b.markRebuilt(joint);
            ++numRebuilt;
            continue;
        }
        buildBatch(batch, lanes);
        for (unsigned lane = 0; lane < JointBatch::kWidth; ++lane)
            if (lanes >> lane & 1u) b.markRebuilt(batch.joints[lane]);
        numRebuilt += static_cast<unsigned>(__builtin_popcount(lanes));
    }
    for (const std::uint32_t joint : plan.singleJoints)
        if (jointDirty[joint])
        {
            buildOne(joint);
            b.markRebuilt(joint);
            ++numRebuilt;
        }
    return numRebuilt;
}

} // namespace

glm::dmat4 computeJointMatrix(const JointKinematics& k, const double* dofs)
{
    glm::dmat4 result;
    buildJointMatrixDispatched(k, dofs, TrigInOrder::exact(k, dofs), &result[0][0]);
    return result;
}

OSGACTOR_HOT_PATH void writeJointMatrix(const JointKinematics& k, const double* dofs, double* local)
{
    FastSinCosRangeGuard guard;
    buildJointMatrixDispatched(k, dofs, TrigInOrder::inFastRange(k, dofs, guard), local);
    if (!guard.passed()) buildJointMatrixDispatched(k, dofs, TrigInOrder::exact(k, dofs), local);
}

bool LocalMatricesJob::validate() const
{
    if (!definition) return false;
    const std::size_t numJoints = definition->getNumJoints();
    return dofs.size() == definition->getNumDofs() && jointDirty.size() == numJoints && local.size() == numJoints &&
           localChanged.size() == numJoints && modelStale.size() == numJoints;
}

bool LocalMatricesJob::run() const
{
    if (!validate()) return false;
    const unsigned rebuilt = buildLocalMatrices(LocalMatricesBuffers{*definition, dofs.data(), jointDirty.data(),
                                                                     local.data(), localChanged.data(),
                                                                     modelStale.data()});
    if (numRebuilt) *numRebuilt = rebuilt;
    return true;
}

} // namespace osgActor
