// One frame of retargeting, in four passes over flat arrays (docs/retargeting.md, "How it works"):
// 1. the source's forward kinematics, each joint's model matrix its parent's turned by its rotations (poseSource);
// 2. per target joint, parents first, the model rotation its plan asks for (desired), as if every parent took its own
//    exactly: a product or two from the rig's constants (a joint that follows a source joint takes it in pass 1);
// 3. the Euler fits of the joints with three rotations, four joints to a vector (EulerLanes.h), each from its local
//    rotation under its parent's desired rotation; a lane that needs more (a limit, gimbal lock, the second solution)
//    is left to the scalar fit; and the Copy joints' angles, four joints to a vector, checked against the limits;
// 4. depth by depth, each joint's DOFs and actual model matrix: the Euler lanes' angles where its parent took its
//    desired rotation; for joints with one or two rotations (a knee, an ankle), the fits of the depth's axis batches,
//    four joints to a vector (AxisLanes.h), under their parents' actual rotations; else the scalar fit under the
//    parent's actual rotation, so an inexact parent's error does not spread.
// Rotations are handled as columns of four doubles (RotationColumns.h); the run is built for x86-64-v3 and the
// baseline (HotPath.h).
#include <osgActor/core/retarget/RetargetJob>
#include <osgActor/core/retarget/JointRotationFit>
#include <osgActor/core/ik/IkKinematics>

#include "../detail/HotPath.h"
#include "../detail/JointMatrixKernel.h"
#include "AxisLanes.h"
#include "EulerLanes.h"
#include "RotationColumns.h"

#include <glm/gtc/quaternion.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>

namespace osgActor {

using namespace retarget_detail;

void RetargetWorkspace::resize(const RetargetRig& rig)
{
    const unsigned numTarget = rig.getTargetDefinition()->getNumJoints();
    const RetargetJobTables& tables = rig.getJobTables();
    sourceModels.assign(tables.sourcePosed.size() + 1, glm::dmat4(1.0));
    sourceSlots = tables.sourceSlots;
    targetModels.assign(numTarget, glm::dmat4(1.0));
    targetExact.assign(numTarget, 0);
    scratch.sourceSines.assign(4 * tables.sourceAngleColumns.size(), 0.0);
    scratch.sourceCosines.assign(4 * tables.sourceAngleColumns.size(), 1.0);
    scratch.desired.assign(std::size_t(numTarget) * kRotationDoubles, 0.0);
    scratch.batchLanes.assign(16 * (tables.eulerBatches.size() + tables.copyBatches.size() + 1), 0.0);
    scratch.axisLanes.assign(32 * tables.axisBatches.size(), 0.0);
    scratch.asDesired.assign(numTarget, 0);
}

bool RetargetWorkspace::fits(const RetargetRig& rig) const
{
    const std::size_t numSource = rig.getSourceDefinition()->getNumJoints();
    const std::size_t numTarget = rig.getTargetDefinition()->getNumJoints();
    const Scratch& s = scratch;
    const RetargetJobTables& tables = rig.getJobTables();
    const std::size_t numTrig = 4 * tables.sourceAngleColumns.size();
    return sourceModels.size() == tables.sourcePosed.size() + 1 && sourceSlots.size() == numSource &&
           s.sourceSines.size() == numTrig && s.sourceCosines.size() == numTrig &&
           targetModels.size() == numTarget &&
           targetExact.size() == numTarget && s.desired.size() == numTarget * kRotationDoubles &&
           s.batchLanes.size() == 16 * (tables.eulerBatches.size() + tables.copyBatches.size() + 1) &&
           s.axisLanes.size() == 32 * tables.axisBatches.size() &&
           s.asDesired.size() == numTarget;
}

namespace {

/** Whether every value's magnitude is at most bound (false for NaN), four values to a vector, with no branch per value
  * and no chain of one comparison after another. */
OSGACTOR_HOT_PATH bool allWithin(const double* values, std::size_t count, double bound)
{
    ColumnSignedBits outside = {0, 0, 0, 0};
    std::size_t i = 0;
    // Two vectors a step: half the loop's counting and branching per value.
    for (; i + 8 <= count; i += 8)
        outside |= ~((absColumn(loadColumn(values + i)) <= bound) & (absColumn(loadColumn(values + i + 4)) <= bound));
    for (; i + 4 <= count; i += 4) outside |= !(absColumn(loadColumn(values + i)) <= bound);
    bool valid = (outside[0] | outside[1] | outside[2] | outside[3]) == 0;
    for (; i < count; ++i) valid &= std::abs(values[i]) <= bound;
    return valid;
}

/** Whether every value is finite: x * 0 is 0 for a finite x and NaN for an infinite or NaN one, so the sum of those
  * is 0 exactly when all are finite, one multiply-add per four values (two sums, so they overlap). The file is built
  * without -ffinite-math-only, which keeps x * 0 from being folded to 0. */
OSGACTOR_HOT_PATH bool allFinite(const double* values, std::size_t count)
{
    Column sum0 = {0.0, 0.0, 0.0, 0.0}, sum1 = sum0;
    std::size_t i = 0;
    for (; i + 8 <= count; i += 8)
    {
        sum0 += loadColumn(values + i) * 0.0;
        sum1 += loadColumn(values + i + 4) * 0.0;
    }
    for (; i + 4 <= count; i += 4) sum0 += loadColumn(values + i) * 0.0;
    const Column sum = sum0 + sum1;
    double total = (sum[0] + sum[1]) + (sum[2] + sum[3]);
    for (; i < count; ++i) total += values[i] * 0.0;
    return total == 0.0;
}

} // namespace

bool RetargetJob::validate() const
{
    if (!rig || !workspace || !workspace->fits(*rig)) return false;
    if (sourceDofs.size() != rig->getSourceDefinition()->getNumDofs()) return false;
    if (targetDofs.size() != rig->getTargetDefinition()->getNumDofs()) return false;
    return allWithin(sourceDofs.data(), sourceDofs.size(), kMaxDofMagnitude) &&
           allFinite(targetDofs.data(), targetDofs.size());
}

namespace {

/** Pass 1: the source's model matrices, of the joints the rig reads (RetargetJobTables::sourcePosed), parents first.
  * The sines and cosines of their angles first, four consecutive DOFs at a time; then each joint's model matrix from
  * its parent's: for a joint that only turns (RetargetSourceJoint::turnsOnly), the parent's rotation columns turned by
  * its rotations one after another (each mixes two columns) and its origin moved by the offset, with no local matrix
  * built; for the others (a root that slides), the local matrix (JointMatrixKernel.h, as LocalMatricesJob builds it)
  * times the parent's. A root's parent frame is the rig's alignment A, so every model matrix comes out turned (A * M,
  * RetargetWorkspace::sourceModels) with no product for A but the roots'. Joint after joint down a chain, the parent's
  * columns stay in registers (as in LocalToModelJob). */
OSGACTOR_INLINE void poseSource(const RetargetRig& rig, const RetargetJobTables& tables, const double* dofs,
                                RetargetWorkspace& w)
{
    using namespace joint_matrix_detail;
    const ActorDefinition& source = *rig.getSourceDefinition();
    RetargetWorkspace::Scratch& s = w.scratch;
    w.sourceAlignment = rig.isAlignmentIdentity() ? nullptr : &rig.getAlignment();
    // In locals, as in placeJoints.
    double* const sines = s.sourceSines.data();
    double* const cosines = s.sourceCosines.data();
    const std::uint32_t* const angleColumns = tables.sourceAngleColumns.data();
    const std::size_t numColumns = tables.sourceAngleColumns.size();
    double padded[4] = {0.0, 0.0, 0.0, 0.0};
    const double* angles = dofs;
    if (source.getNumDofs() < 4)
    {
        std::copy(dofs, dofs + source.getNumDofs(), padded);
        angles = padded;
    }
    // The angles' range is checked once after the sweep, not column by column (as LocalMatricesJob does); a pose with
    // an angle beyond the fast range (it almost never comes) is swept again with sinCosColumn, which takes any.
    FastSinCosRangeGuard guard;
    for (std::size_t c = 0; c < numColumns; ++c)
    {
        const Column x = loadColumn(angles + angleColumns[c]);
        guard.check(x);
        Column sine, cosine;
        sinCosColumnInFastRange(x, sine, cosine);
        storeColumn(sines + 4 * c, sine);
        storeColumn(cosines + 4 * c, cosine);
    }
    if (!guard.passed())
        for (std::size_t c = 0; c < numColumns; ++c)
        {
            Column sine, cosine;
            sinCosColumn(loadColumn(angles + angleColumns[c]), sine, cosine);
            storeColumn(sines + 4 * c, sine);
            storeColumn(cosines + 4 * c, cosine);
        }

    const RetargetSourceJoint* const joints = tables.sourceJoints.data();
    const std::uint32_t* const posed = tables.sourcePosed.data();
    const JointKinematics* const kinematics = source.getAllKinematics().data();
    glm::dmat4* const models = w.sourceModels.data();
    const double* const postRotations = tables.postRotations.data();
    double* const desired = s.desired.data();
    const RotationColumns alignment = loadRotation(tables.alignment);
    const AffineColumns rootFrame{{alignment.c[0], alignment.c[1], alignment.c[2], Column{0.0, 0.0, 0.0, 1.0}}};
    AffineColumns previous = rootFrame;
    // The parent frame of joint i, in previous: the joint just composed (still in registers) where the parent is the
    // joint before.
    const auto loadParentFrame = [&](unsigned i) OSGACTOR_INLINE_LAMBDA {
        const int parent = joints[i].parent;
        if (parent + 1 != static_cast<int>(i)) previous = parent < 0 ? rootFrame : loadAffine(&models[parent][0][0]);
    };
    // Joint i's model matrix, in previous, stored; and the desired rotation of the target joint that follows it (see
    // desireRotations), from the registers.
    const auto storeModel = [&](unsigned i) OSGACTOR_INLINE_LAMBDA {
        storeAffine(&models[i][0][0], previous);
        const RetargetSourceJoint& joint = joints[i];
        const std::uint32_t follower = joint.follower;
        if (follower != RetargetSourceJoint::kNoFollower)
        {
            const RotationColumns rotation{{previous.c[0], previous.c[1], previous.c[2]}};
            storeRotation(desired + follower * kRotationDoubles,
                          joint.followerTurns
                              ? multiply(rotation, loadRotation(postRotations + follower * kRotationDoubles))
                              : rotation);
        }
    };
    // Run by run (RetargetSourceRun): one jump to the code for a run's rotation sequence, not one a joint.
    for (const RetargetSourceRun& run : tables.sourceRuns)
    {
        if (run.turnsOnly)
            withRotationSequence(run.rotationSequence, [&](auto sequence) OSGACTOR_INLINE_LAMBDA {
                using Axes = SequenceAxes<decltype(sequence)::value>;
                for (unsigned i = run.first; i < run.end; ++i)
                {
                    loadParentFrame(i);
                    const RetargetSourceJoint& joint = joints[i];
                    const Column origin = combineColumns(previous.c[0], previous.c[1], previous.c[2], joint.offset[0],
                                                         joint.offset[1], joint.offset[2]) +
                                          previous.c[3];
                    RotationColumns turned{{previous.c[0], previous.c[1], previous.c[2]}};
                    if constexpr (Axes::count >= 1)
                        postRotate(turned, Axes::first, cosines[joint.trig[0]], sines[joint.trig[0]]);
                    if constexpr (Axes::count >= 2)
                        postRotate(turned, Axes::second, cosines[joint.trig[1]], sines[joint.trig[1]]);
                    if constexpr (Axes::count >= 3)
                        postRotate(turned, Axes::third, cosines[joint.trig[2]], sines[joint.trig[2]]);
                    previous = AffineColumns{{turned.c[0], turned.c[1], turned.c[2], origin}};
                    storeModel(i);
                }
            });
        else
            for (unsigned i = run.first; i < run.end; ++i)
            {
                loadParentFrame(i);
                const RetargetSourceJoint& joint = joints[i];
                const JointKinematics& k = kinematics[posed[i]];
                TrigInOrder trig{};
                for (unsigned r = 0; r < k.numRotations; ++r)
                {
                    trig.sines[r] = sines[joint.trig[r]];
                    trig.cosines[r] = cosines[joint.trig[r]];
                }
                alignas(32) double local[16] = {};
                buildJointMatrixDispatched(k, dofs, trig, local);
                previous = multiplyAffineColumns(previous, local);
                storeModel(i);
            }
    }
}

/** The model-space rotation change of a source joint since the rest pose, as a quaternion; identity for -1. */
glm::dquat changeSinceRest(const RetargetRig& rig, const RetargetWorkspace& w, int joint)
{
    if (joint < 0) return glm::dquat(1.0, 0.0, 0.0, 0.0);
    const unsigned j = static_cast<unsigned>(joint);
    return glm::quat_cast(w.sourceRotation(j) * glm::transpose(glm::dmat3(rig.getSourceRestModels()[j])));
}

/** Pass 2: the other target joints' desired model rotations (see RetargetJointPlan), parents first; a joint at rest
  * under its parent's desired rotation. */
OSGACTOR_INLINE void desireRotations(const RetargetRig& rig, RetargetWorkspace& w)
{
    const ActorDefinition& target = *rig.getTargetDefinition();
    const RetargetJobTables& tables = rig.getJobTables();
    // The source's model rotations are stored turned by the alignment already (poseSource): A * R_s(b). The tables in
    // locals, as in placeJoints.
    const glm::dmat4* const turnedSourceModels = w.sourceModels.data();
    const RetargetDesire* const desire = tables.desire.data();
    const std::uint32_t* const desireSlot = tables.desireSlot.data();
    const double* const postRotations = tables.postRotations.data();
    const double* const restLocalRotations = tables.restLocalRotations.data();
    const int* const parents = target.getParents().data();
    double* const desired = w.scratch.desired.data();
    // The joints that follow a source joint the forward kinematics has stored already (RetargetSourceJoint::follower).
    for (const std::uint32_t t : tables.desireJoints)
    {
        RotationColumns d;
        switch (desire[t])
        {
        case RetargetDesire::Follow: d = loadRotation(turnedSourceModels[desireSlot[t]]); break;
        case RetargetDesire::FollowThenPost:
            d = multiply(loadRotation(turnedSourceModels[desireSlot[t]]),
                         loadRotation(postRotations + t * kRotationDoubles));
            break;
        case RetargetDesire::Rest:
            d = loadRotation(restLocalRotations + t * kRotationDoubles);
            if (parents[t] >= 0) d = multiply(loadRotation(desired + parents[t] * kRotationDoubles), d);
            break;
        default:
        {
            const RetargetJointPlan& plan = rig.getPlan(t);
            if (plan.weight == 1.0)
            {
                // No source joint: A * postRotation.
                d = loadRotation(tables.alignment);
                if (!plan.postIsIdentity) d = multiply(d, loadRotation(postRotations + t * kRotationDoubles));
                break;
            }
            const glm::dmat3 blended = rig.getAlignment() *
                                       glm::mat3_cast(glm::slerp(changeSinceRest(rig, w, plan.sourceA),
                                                                 changeSinceRest(rig, w, plan.sourceB), plan.weight)) *
                                       plan.postRotation;
            double columns[kRotationDoubles];
            storeRotation(columns, blended);
            d = loadRotation(columns);
        }
        }
        storeRotation(desired + t * kRotationDoubles, d);
    }
}

/** The frame a joint's rotation DOFs turn in: its parent's model rotation times its offset rotation. */
OSGACTOR_INLINE RotationColumns jointFrame(const RetargetJobTables& tables, unsigned joint, bool hasParent,
                                           const RotationColumns& parentRotation)
{
    if (tables.offsetIsIdentity[joint]) return parentRotation;
    const RotationColumns offset = loadRotation(&tables.offsetRotations[joint * kRotationDoubles]);
    return hasParent ? multiply(parentRotation, offset) : offset;
}

/** The identity as columns of four, for a root's parent rotation read from memory at a runtime column. */
alignas(32) constexpr double kIdentityColumns[kRotationDoubles] = {1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0,
                                                                   0.0, 0.0, 1.0, 0.0};

/** A batch's results as whole columns (RetargetWorkspace::Scratch::batchLanes): its three angle columns, then 1.0
  * where a lane's stand and 0.0 where not (the mask's bits kept where 1.0's are). */
OSGACTOR_INLINE void storeLanes(double* lanes, const Column (&angles)[3], LaneMask stand)
{
    for (unsigned r = 0; r < 3; ++r) storeColumn(lanes + 4 * r, angles[r]);
    const Column one = {1.0, 1.0, 1.0, 1.0};
    storeColumn(lanes + 12, reinterpret_cast<Column>(stand & reinterpret_cast<LaneMask>(one)));
}

/** Pass 3: the Euler fits of the batches' joints, four at a time, each under its parent's desired rotation. Batches go
  * in groups: the group's arctangents (each a long chain of dependent operations: divisions, a polynomial) run one
  * after another, so the processor overlaps them, which it cannot do across one batch's whole fit. */
OSGACTOR_INLINE void fitEulerBatches(const RetargetRig& rig, const double* dofs, RetargetWorkspace& w)
{
    constexpr std::size_t kGroup = 4;
    const ActorDefinition& target = *rig.getTargetDefinition();
    const RetargetJobTables& tables = rig.getJobTables();
    // The tables in locals, as in placeJoints: the byte flags written below would otherwise make them be read again.
    const RetargetEulerBatch* const batches = tables.eulerBatches.data();
    const std::size_t numBatches = tables.eulerBatches.size();
    const int* const parents = target.getParents().data();
    const std::uint8_t* const offsetIsIdentity = tables.offsetIsIdentity.data();
    const double* const offsetRotations = tables.offsetRotations.data();
    const double* const desiredRotations = w.scratch.desired.data();
    double* const batchLanes = w.scratch.batchLanes.data();
    for (std::size_t first = 0; first < numBatches; first += kGroup)
    {
        const std::size_t numInGroup = std::min(kGroup, numBatches - first);
        EulerArctangents in[kGroup];
        for (std::size_t b = 0; b < numInGroup; ++b)
        {
            const RetargetEulerBatch& batch = batches[first + b];
            EulerLaneColumns lanes[RetargetEulerBatch::kWidth];
            // Lanes past the last joint repeat it (RetargetEulerBatch), and are worked out as the others, with no
            // branch (cheaper than copying its six columns; their results are never written).
            for (unsigned lane = 0; lane < RetargetEulerBatch::kWidth; ++lane)
            {
                // The joint's frame (jointFrame) is its parent's desired rotation times its offset rotation.
                const unsigned t = batch.joints[lane];
                const int parent = parents[t];
                const double* const desired = desiredRotations + t * kRotationDoubles;
                const double* const parentDesired =
                    parent >= 0 ? desiredRotations + static_cast<unsigned>(parent) * kRotationDoubles
                                : kIdentityColumns;
                for (unsigned r = 0; r < 3; ++r) lanes[lane].desired[r] = loadColumn(desired + batch.columnAt[r][lane]);
                if (offsetIsIdentity[t])
                    for (unsigned r = 0; r < 3; ++r)
                        lanes[lane].frame[r] = loadColumn(parentDesired + batch.columnAt[r][lane]);
                else
                {
                    const RotationColumns parentRotation = loadRotation(parentDesired);
                    const double* const offset = offsetRotations + t * kRotationDoubles;
                    for (unsigned r = 0; r < 3; ++r)
                    {
                        const double* const column = offset + batch.columnAt[r][lane];
                        lanes[lane].frame[r] = combine(parentRotation, column[0], column[1], column[2]);
                    }
                }
            }
            in[b] = eulerArctangents(batch, lanes);
        }
        Column angles[kGroup][3];
        for (std::size_t b = 0; b < numInGroup; ++b)
            for (unsigned r = 0; r < 3; ++r) angles[b][r] = arctangent2Lanes(in[b].y[r], in[b].x[r], in[b].invalid);
        for (std::size_t b = 0; b < numInGroup; ++b)
        {
            const RetargetEulerBatch& batch = batches[first + b];
            const EulerLanesFit fit = fitEulerLanes(batch, angles[b], in[b].invalid, dofs);
            storeLanes(batchLanes + 16 * (first + b), fit.angles, fit.fitted);
        }
    }
}

/** Pass 3, for the copy batches' joints, four at a time: their source joints' angles, fitted where all of a joint's
  * lie within its limits. */
OSGACTOR_INLINE void takeCopyBatches(const RetargetJobTables& tables, const double* sourceValues, RetargetWorkspace& w)
{
    // In locals, as in placeJoints. The copy batches' results come after the Euler batches' (RetargetJobTables::laneAt).
    double* lanes = w.scratch.batchLanes.data() + 16 * tables.eulerBatches.size();
    for (const RetargetCopyBatch& batch : tables.copyBatches)
    {
        Column angles[3];
        LaneMask within = ~LaneMask{};
        for (unsigned r = 0; r < 3; ++r)
        {
            angles[r] = gatherLanes(sourceValues, batch.sourceDof[r]);
            within &= angles[r] >= loadColumn(batch.min[r]) && angles[r] <= loadColumn(batch.max[r]);
        }
        storeLanes(lanes, angles, within);
        lanes += 16;
    }
}

/** frame * R_a1 * R_a2 * R_a3 for a joint's rotation DOFs (product order): its model rotation from its frame. */
OSGACTOR_INLINE RotationColumns rotateByDofs(RotationColumns frame, const JointKinematics& k, const double* dofs)
{
    if (k.numRotations == 0) return frame;
    double angles[4] = {0.0, 0.0, 0.0, 0.0};
    for (unsigned r = 0; r < k.numRotations; ++r) angles[r] = dofs[k.rotationDof[r]];
    Column sines, cosines;
    sinCosColumn(loadColumn(angles), sines, cosines);
    for (unsigned r = 0; r < k.numRotations; ++r) postRotate(frame, k.rotationAxis[r], cosines[r], sines[r]);
    return frame;
}

/** The fits of an axis batch's joints (one or two rotations), four at a time, each under its parent's actual model
  * rotation: the parents, a depth up, are placed. */
OSGACTOR_INLINE void fitAxisBatch(std::uint32_t index, const ActorDefinition& target, const RetargetJobTables& tables,
                                  const double* dofs, RetargetWorkspace& w)
{
    const RetargetAxisBatch& batch = tables.axisBatches[index];
    RetargetWorkspace::Scratch& s = w.scratch;
    double local[RetargetAxisBatch::kWidth][kRotationDoubles];
    const double* lanes[RetargetAxisBatch::kWidth];
    for (unsigned lane = 0; lane < RetargetAxisBatch::kWidth; ++lane)
    {
        lanes[lane] = local[lane < batch.numJoints ? lane : batch.numJoints - 1];
        if (lane >= batch.numJoints) continue;
        const unsigned t = batch.joints[lane];
        const int parent = target.getParent(t);
        const RotationColumns parentRotation =
            parent >= 0 ? loadRotation(w.targetModels[static_cast<unsigned>(parent)]) : identityColumns();
        const RotationColumns frame = jointFrame(tables, t, parent >= 0, parentRotation);
        storeRotation(local[lane], multiply(transpose(frame), loadRotation(&s.desired[t * kRotationDoubles])));
    }
    const AxisLanesFit fit = fitAxisLanes(batch, lanes, dofs);
    // As whole columns (RetargetWorkspace::Scratch::axisLanes); a batch of one rotation leaves its second columns
    // unwritten.
    double* const out = s.axisLanes.data() + 32 * index;
    for (unsigned r = 0; r < batch.numRotations; ++r)
    {
        storeColumn(out + 4 * r, fit.angles[r]);
        storeColumn(out + 8 + 4 * r, fit.cosines[r]);
        storeColumn(out + 16 + 4 * r, fit.sines[r]);
    }
    const Column one = {1.0, 1.0, 1.0, 1.0};
    storeColumn(out + 24, reinterpret_cast<Column>(fit.fitted & reinterpret_cast<LaneMask>(one)));
}

/** The root's translation DOFs, from where the source's root goes (RetargetRig::mapPosition) less its offset, turned
  * back through whatever of its rotations acts on them; what they cannot reach is dropped. Returns its origin in its
  * parent's frame. */
glm::dvec3 placeRoot(const RetargetRig& rig, const RetargetWorkspace& w, unsigned t, const glm::dmat3& parentRotation,
                     const glm::dvec3& parentPosition, const glm::dmat3& localRotation, double* dofs)
{
    const ActorDefinition& target = *rig.getTargetDefinition();
    const JointKinematics& k = target.getKinematics(t);
    const glm::dmat3& offsetRotation = rig.getTargetOffsetRotations()[t];
    const glm::dvec3 offset(k.offset[3]);
    const glm::dvec3 goal =
        rig.mapPosition(w.sourcePosition(static_cast<unsigned>(rig.getSourceRoot())));
    const glm::dvec3 inParent = glm::transpose(parentRotation) * (goal - parentPosition) - offset;
    const bool beforeRotation = k.translationMode == TranslationMode::BeforeRotation;
    const glm::dvec3 slide = glm::transpose(beforeRotation ? offsetRotation : localRotation) * inParent;
    for (unsigned axis = 0; axis < 3; ++axis)
        if (k.translationDof[axis] >= 0)
        {
            const unsigned dof = static_cast<unsigned>(k.translationDof[axis]);
            dofs[dof] = target.clampToLimits(dof, slide[axis]);
        }
    return offset + (beforeRotation ? offsetRotation : localRotation) * jointSlide(k, dofs);
}

/** What the placement reads and writes per joint, as plain pointers taken once per frame into locals: the byte flags
  * it writes (asDesired, targetExact) may alias anything, so pointers read from the vectors would be read again after
  * each joint; locals whose address is never taken stay in registers. */
struct PlacementArrays
{
    const JointKinematics* kinematics;
    const int* parents;
    const RetargetPlacement* placement;
    const double* desired;
    const double* batchLanes;
    const std::uint32_t* laneAt;
    const double* axisLanes;
    const double* rest;
    const double* origins;
    const std::uint8_t* originMoves;
    const double* restLocalRotations;
    std::uint8_t* asDesired;
    std::uint8_t* targetExact;
    glm::dmat4* targetModels;
};

OSGACTOR_INLINE PlacementArrays placementArrays(const RetargetRig& rig, RetargetWorkspace& w)
{
    const ActorDefinition& target = *rig.getTargetDefinition();
    const RetargetJobTables& tables = rig.getJobTables();
    RetargetWorkspace::Scratch& s = w.scratch;
    return {target.getAllKinematics().data(), target.getParents().data(), tables.placement.data(),
            s.desired.data(), s.batchLanes.data(), tables.laneAt.data(), s.axisLanes.data(),
            rig.getTargetRestDofs().data(), tables.origins.data(), tables.originMoves.data(),
            tables.restLocalRotations.data(), s.asDesired.data(), w.targetExact.data(), w.targetModels.data()};
}

/** One target joint's DOFs and model matrix, its parent placed. Returns whether it counts as inexact (the source
  * drives it, and it could not take its desired rotation). */
OSGACTOR_INLINE bool placeJoint(const RetargetRig& rig, const PlacementArrays& a, unsigned t,
                                const double* __restrict sourceValues, double* __restrict targetValues,
                                RetargetWorkspace& w)
{
    const RetargetJobTables& tables = rig.getJobTables();
    const JointKinematics& k = a.kinematics[t];
    const int parent = a.parents[t];
    const bool hasParent = parent >= 0;
    const unsigned p = hasParent ? static_cast<unsigned>(parent) : 0;
    const RotationColumns parentRotation = hasParent ? loadRotation(a.targetModels[p]) : identityColumns();
    const Column parentPosition = hasParent ? loadColumn(&a.targetModels[p][3][0]) : Column{0.0, 0.0, 0.0, 1.0};
    const bool parentExact = !hasParent || a.targetExact[p] != 0;
    const bool parentAsDesired = !hasParent || a.asDesired[p] != 0;
    const RotationColumns desired = loadRotation(a.desired + t * kRotationDoubles);

    const RetargetPlacement how = a.placement[t];
    RotationColumns rotation;
    bool exact = false;
    // An Euler or copy batch's lane: its angles at lane[0], lane[4], lane[8], whether they stand at lane[12].
    const double* const lane = a.batchLanes + a.laneAt[t];
    if (how == RetargetPlacement::Euler && lane[12] != 0.0 && parentAsDesired)
    {
        for (unsigned r = 0; r < 3; ++r) targetValues[k.rotationDof[r]] = lane[4 * r];
        exact = true;
        rotation = desired;
    }
    else if (how == RetargetPlacement::Rest)
    {
        for (unsigned r = 0; r < k.numRotations; ++r) targetValues[k.rotationDof[r]] = a.rest[k.rotationDof[r]];
        // Under a parent at its desired rotation (or none), the desired rotation is this product already.
        rotation = parentAsDesired
                       ? desired
                       : multiply(parentRotation, loadRotation(a.restLocalRotations + t * kRotationDoubles));
    }
    else if (how == RetargetPlacement::Copy && parentExact && lane[12] != 0.0)
    {
        // The same local frames as the source joint's, and its angles within the limits (takeCopyBatches). Three
        // rotations (the usual case) in straight-line code, not a loop of a count read from memory.
        if (k.numRotations == 3)
            for (unsigned r = 0; r < 3; ++r) targetValues[k.rotationDof[r]] = lane[4 * r];
        else
            for (unsigned r = 0; r < k.numRotations; ++r) targetValues[k.rotationDof[r]] = lane[4 * r];
        exact = true;
        rotation = desired;
    }
    else if (how == RetargetPlacement::Copy && parentExact)
    {
        // The same local frames as the source joint's: its angles, turned or clamped into the limits.
        const ActorDefinition& source = *rig.getSourceDefinition();
        const ActorDefinition& target = *rig.getTargetDefinition();
        const JointKinematics& sk = source.getKinematics(static_cast<unsigned>(rig.getPlans()[t].sourceB));
        bool clamped = false;
        for (unsigned r = 0; r < k.numRotations; ++r)
        {
            const unsigned dof = k.rotationDof[r];
            const double angle = sourceValues[sk.rotationDof[r]];
            double& value = targetValues[dof];
            if (!turnWithinLimits(angle, target.getDofRangeMin(dof), target.getDofRangeMax(dof), angle, value))
            {
                value = fitAngleToLimits(angle, target.getDofRangeMin(dof), target.getDofRangeMax(dof), angle);
                clamped = true;
            }
        }
        exact = !clamped;
        rotation =
            exact ? desired : rotateByDofs(jointFrame(tables, t, hasParent, parentRotation), k, targetValues);
    }
    else if (how == RetargetPlacement::Axis && a.axisLanes[a.laneAt[t] + 24] != 0.0)
    {
        // An axis batch's lane: its angles at [0] and [4], their cosines at [8] and [12], sines at [16] and [20].
        const double* const axisLane = a.axisLanes + a.laneAt[t];
        // Fewer than three rotations: the nearest the joint can come, never exact (as fitJointRotationDofs).
        rotation = jointFrame(tables, t, hasParent, parentRotation);
        for (unsigned r = 0; r < k.numRotations; ++r)
        {
            targetValues[k.rotationDof[r]] = axisLane[4 * r];
            postRotate(rotation, k.rotationAxis[r], axisLane[8 + 4 * r], axisLane[16 + 4 * r]);
        }
    }
    else
    {
        const RotationColumns frame = jointFrame(tables, t, hasParent, parentRotation);
        exact = fitJointRotationDofs(*rig.getTargetDefinition(), t, toMat3(multiply(transpose(frame), desired)),
                                     targetValues);
        rotation = exact ? desired : rotateByDofs(frame, k, targetValues);
    }
    const bool counted = !exact && how != RetargetPlacement::Rest && k.numRotations > 0;
    a.asDesired[t] = exact || (how == RetargetPlacement::Rest && parentAsDesired) ? 1 : 0;

    Column origin = loadColumn(a.origins + 4 * t);
    if (a.originMoves[t])
    {
        const glm::dmat3 parentMatrix = toMat3(parentRotation);
        const glm::dmat3 localRotation = glm::transpose(parentMatrix) * toMat3(rotation);
        glm::dvec3 moved;
        if (static_cast<int>(t) == rig.getTargetRoot() && rig.getSourceRoot() >= 0)
            moved = placeRoot(rig, w, t, parentMatrix, glm::dvec3(parentPosition[0], parentPosition[1],
                                                                  parentPosition[2]),
                              localRotation, targetValues);
        else
            moved = glm::dvec3(k.offset[3]) + localRotation * jointSlide(k, targetValues);
        origin = Column{moved.x, moved.y, moved.z, 0.0};
    }
    glm::dmat4& model = a.targetModels[t];
    storeRotation(&model[0][0], rotation);
    storeColumn(&model[3][0], parentPosition + combine(parentRotation, origin));
    a.targetExact[t] = exact ? 1 : 0;
    return counted;
}

/** Pass 4: depth by depth, the fits of its axis batches (their joints' parents are placed, and their joints not yet),
  * then each of its joints (placeJoint). Returns how many joints the source drives came out inexact. */
OSGACTOR_INLINE unsigned placeJoints(const RetargetRig& rig, const double* sourceValues, double* targetValues,
                                     RetargetWorkspace& w)
{
    const ActorDefinition& target = *rig.getTargetDefinition();
    const RetargetJobTables& tables = rig.getJobTables();
    const double* const rest = rig.getTargetRestDofs().data();
    for (const std::uint32_t first : tables.translationTriples)
        std::memcpy(targetValues + first, rest + first, 3 * sizeof(double));
    for (const std::uint32_t dof : tables.translationDofs) targetValues[dof] = rest[dof];
    unsigned numInexact = 0;
    // The bounds and arrays in locals: the joints' byte flags written in the loops could otherwise alias the tables'
    // vectors, and the compiler would read them again on every step.
    const PlacementArrays arrays = placementArrays(rig, w);
    const std::size_t numLevels = tables.levelJoints.empty() ? 0 : tables.levelJoints.size() - 1;
    const std::uint32_t* const levelJoints = tables.levelJoints.data();
    const std::uint32_t* const levelBatches = tables.levelBatches.data();
    const std::uint32_t* const placeOrder = tables.placeOrder.data();
    for (std::size_t level = 0; level < numLevels; ++level)
    {
        const std::uint32_t lastBatch = levelBatches[level + 1], lastJoint = levelJoints[level + 1];
        for (std::uint32_t b = levelBatches[level]; b < lastBatch; ++b)
            fitAxisBatch(b, target, tables, targetValues, w);
        for (std::uint32_t i = levelJoints[level]; i < lastJoint; ++i)
            numInexact += placeJoint(rig, arrays, placeOrder[i], sourceValues, targetValues, w) ? 1 : 0;
    }
    return numInexact;
}

} // namespace

OSGACTOR_HOT_PATH bool RetargetJob::run()
{
    if (!validate()) return false;
    RetargetWorkspace& w = *workspace;
    poseSource(*rig, rig->getJobTables(), sourceDofs.data(), w);
    desireRotations(*rig, w);
    fitEulerBatches(*rig, targetDofs.data(), w);
    takeCopyBatches(rig->getJobTables(), sourceDofs.data(), w);
    numInexact = placeJoints(*rig, sourceDofs.data(), targetDofs.data(), w);
    return true;
}

} // namespace osgActor
