#include <osgActor/core/ActorPose>
#include <osgActor/core/LocalMatricesJob>
#include <osgActor/core/LocalToModelJob>

#include "detail/HotPath.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

namespace osgActor {

namespace {

/** What clampAndStoreDofs found. */
struct StoreCounts
{
    std::uint64_t refused = 0;
    std::uint64_t changed = 0;
};

/** The vectorized half of ActorPose::setDofRange: setDof()'s clamp, NaN and infinity refusal and change test for
  * count consecutive DOFs, without branches; changed[i] is 1 where DOF i took a new value, else 0 (64-bit, the
  * width of the values, so the loop vectorizes without packing). */
OSGACTOR_HOT_PATH StoreCounts clampAndStoreDofs(const double* __restrict values, const double* __restrict mins,
                                                const double* __restrict maxs, double* __restrict dofs,
                                                std::uint64_t* __restrict changed, unsigned count)
{
    std::uint64_t refused = 0, numChanged = 0;
    for (unsigned i = 0; i < count; ++i)
    {
        const double value = values[i];
        const bool finite = std::fabs(value) <= std::numeric_limits<double>::max(); // false for NaN too
        const double clamped = std::min(std::max(value, mins[i]), maxs[i]);
        const double old = dofs[i];
        const double stored = finite ? clamped : old;
        const std::uint64_t dofChanged = stored != old ? 1u : 0u;
        changed[i] = dofChanged;
        dofs[i] = stored;
        refused += finite ? 0u : 1u;
        numChanged += dofChanged;
    }
    return {refused, numChanged};
}

/** jointDirty[j] |= 1 for every joint j in [first, last] with a DOF: a block whose DOFs all changed marks its joints
  * eight at a time. DOFs are numbered joint by joint, so the joints between the first DOF's and the last DOF's have
  * all their DOFs inside the block. (A skeleton has too few joints for the compiler's vector loop, which would run
  * its scalar tail only.) */
void markJointsWithDofs(const DofMask* dofMasks, std::uint8_t* jointDirty, unsigned first, unsigned last)
{
    // Per byte, a mask below 0x80 plus 0x7f reaches bit 7 exactly when the mask is non-zero, and never carries.
    static_assert(kNumDofTypes < 8, "a DOF mask fits in 7 bits");
    constexpr std::uint64_t kLow7 = 0x7f7f7f7f7f7f7f7full, kOnes = 0x0101010101010101ull;
    unsigned j = first;
    for (; j + 8 <= last + 1; j += 8)
    {
        std::uint64_t masks, dirty;
        std::memcpy(&masks, dofMasks + j, 8);
        std::memcpy(&dirty, jointDirty + j, 8);
        dirty |= ((masks + kLow7) >> 7) & kOnes;
        std::memcpy(jointDirty + j, &dirty, 8);
    }
    for (; j <= last; ++j) jointDirty[j] |= dofMasks[j] != 0 ? 1u : 0u;
}

} // namespace

ActorPose::ActorPose(ActorDefinitionPtr definition) : _definition(std::move(definition))
{
    if (!_definition) return;
    takeDefinition();
    _local = LocalMatrices(_numJoints);
    _model.assign(_numJoints, glm::dmat4(1.0));
}

ActorPose::ActorPose(ActorDefinitionPtr definition, PosedAtDefaults) : _definition(std::move(definition))
{
    if (!_definition) return;
    takeDefinition();
    // Every joint is dirty, so the update below writes every local matrix and, from them, every model matrix.
    _local = LocalMatrices::unwritten(_numJoints);
    _model.resize(_numJoints); // default-initialized (AlignedAllocator): not written
    updateMatrices();
}

ActorPose::ActorPose(ActorDefinitionPtr definition, LocalMatricesBuiltAt built) : _definition(std::move(definition))
{
    if (!_definition) return;
    takeDefinition();
    _model.resize(_numJoints); // default-initialized (AlignedAllocator): written by the first updateModelMatrices()
    _local = LocalMatrices::at(std::move(built.targets));
    if (_local.size() != _numJoints)
    {
        _local = LocalMatrices::unwritten(_numJoints);
        updateMatrices();
        return;
    }
    std::fill_n(jointDirtyFlags(), _numJoints, 0);
    std::fill_n(modelStaleFlags(), _numJoints, 1);
    _anyDirty = false;
    _anyModelStale = _numJoints > 0;
    _totalRecomputed = _numJoints;
}

void ActorPose::takeDefinition()
{
    const unsigned numJoints = _definition->getNumJoints();
    _dofs = _definition->getDefaultDofs();
    _dofMins = _definition->getDofRangeMins().data();
    _dofMaxs = _definition->getDofRangeMaxs().data();
    _dofJoints = _definition->getDofJoints().data();
    _dofMasks = _definition->getDofMasks().data();
    _numJoints = numJoints;
    _jointFlags.assign(3 * std::size_t(numJoints), 0);
    std::fill_n(jointDirtyFlags(), numJoints, 1);
    _anyDirty = numJoints > 0;
}

DofWriteStatus ActorPose::setDofs(const double* values, std::size_t count)
{
    if (count != _dofs.size()) return DofWriteStatus::SizeMismatch;
    if (!std::all_of(values, values + count, [](double v) { return std::isfinite(v); }))
        return DofWriteStatus::NotFinite;
    bool anyClamped = false;
    for (unsigned i = 0; i < count; ++i)
        anyClamped = setDof(i, values[i]) == DofWriteStatus::Clamped || anyClamped;
    return anyClamped ? DofWriteStatus::Clamped : DofWriteStatus::Written;
}

unsigned ActorPose::setDofRange(unsigned firstDof, const double* values, unsigned count)
{
    if (firstDof > _dofs.size() || count > _dofs.size() - firstDof) return count;
    // Every array in a local: the dirty flags are bytes, which may alias anything, so members would be reloaded
    // after each flag store.
    const unsigned* const dofJoints = _dofJoints;
    std::uint8_t* const jointDirty = jointDirtyFlags();
    std::uint64_t refused = 0, anyChanged = 0;
    // In blocks, so the change flags stay in a small buffer on the stack.
    constexpr unsigned kBlock = 128;
    std::uint64_t changed[kBlock];
    for (unsigned begin = firstDof, end = firstDof + count; begin < end; begin += kBlock)
    {
        const unsigned blockEnd = std::min(begin + kBlock, end);
        const StoreCounts counts = clampAndStoreDofs(values + (begin - firstDof), _dofMins + begin,
                                                     _dofMaxs + begin, _dofs.data() + begin, changed, blockEnd - begin);
        refused += counts.refused;
        anyChanged |= counts.changed;
        if (counts.changed == blockEnd - begin)
        {
            // A clip playing: every DOF moved.
            markJointsWithDofs(_dofMasks, jointDirty, dofJoints[begin], dofJoints[blockEnd - 1]);
            continue;
        }
        if (counts.changed == 0) continue;
        // Each DOF marks its joint: a joint's DOFs are consecutive, so its flag stays in a register-sized store
        // buffer, and this costs less than finding where each joint's DOFs start and end in the block.
#pragma GCC unroll 4
        for (unsigned i = begin; i < blockEnd; ++i)
            jointDirty[dofJoints[i]] |= static_cast<std::uint8_t>(changed[i - begin]);
    }
    _anyDirty = _anyDirty || anyChanged != 0;
    return static_cast<unsigned>(refused);
}

void ActorPose::resetDofs()
{
    if (_definition) setDofs(_definition->getDefaultDofs().data(), _definition->getNumDofs());
}

void ActorPose::markAllJointsDirty()
{
    std::fill_n(jointDirtyFlags(), _numJoints, 1);
    _anyDirty = _numJoints > 0;
}

unsigned ActorPose::updateMatrices()
{
    const unsigned numRebuilt = updateLocalMatrices();
    updateModelMatrices();
    return numRebuilt;
}

unsigned ActorPose::updateLocalMatrices()
{
    if (!_anyDirty) return 0;
    unsigned numRebuilt = 0;
    LocalMatricesJob job;
    job.definition = _definition.get();
    job.dofs = _dofs;
    job.jointDirty = {jointDirtyFlags(), _numJoints};
    job.local = {_local.targets(), _numJoints};
    job.localChanged = {localChangedFlags(), _numJoints};
    job.modelStale = {modelStaleFlags(), _numJoints};
    job.numRebuilt = &numRebuilt;
    job.run();
    _anyDirty = false;
    _anyModelStale = _anyModelStale || numRebuilt > 0;
    _anyLocalChanged = _anyLocalChanged || numRebuilt > 0;
    _allLocalsChanged = _allLocalsChanged || (numRebuilt == _numJoints && numRebuilt > 0);
    _totalRecomputed += numRebuilt;
    return numRebuilt;
}

void ActorPose::updateModelMatrices()
{
    if (!_anyModelStale) return;
    LocalToModelJob job;
    job.parents = _definition->getParents();
    job.local = {_local.targets(), _numJoints};
    job.modelStale = {modelStaleFlags(), _numJoints};
    job.model = _model;
    job.run();
    _anyModelStale = false;
}

} // namespace osgActor
