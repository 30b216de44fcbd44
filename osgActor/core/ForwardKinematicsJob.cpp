// The per-frame hot path. Matrices are glm::dmat4 in memory (column-major, 16 doubles) but are handled here as raw
// affine arrays: the bottom row of every joint matrix is (0 0 0 1), so a product is a 3x3 rotation product plus a
// translation, not a full 4x4 product. This file is compiled with -O3 and its per-frame loops are built twice
// (AVX2+FMA and the x86-64 baseline), the right ones chosen when the library is loaded.
#include <osgActor/core/ForwardKinematicsJob>

#include "Column.h"
#include "HotPath.h"
#include "SinCosColumn.h"

#include <cmath>
#include <cstring>
#include <type_traits>

namespace osgActor {

namespace {

/** x a0 + y a1 + z a2: a point or direction (x, y, z) taken through the three axis columns of a matrix. Every product
  * of matrices here is columns of this. */
OSGACTOR_INLINE Column combineColumns(Column a0, Column a1, Column a2, double x, double y, double z)
{
    return a0 * x + a1 * y + a2 * z;
}

/** Four joints' 3-vectors, one joint per lane: x holds the four x components, and so on. */
struct LaneVector3
{
    Column x, y, z;
};

OSGACTOR_INLINE LaneVector3 operator*(Column s, const LaneVector3& v) { return {s * v.x, s * v.y, s * v.z}; }
OSGACTOR_INLINE LaneVector3 operator+(const LaneVector3& a, const LaneVector3& b)
{
    return {a.x + b.x, a.y + b.y, a.z + b.z};
}

/** A 3x3 rotation as three columns. Vector3 is a Column (x, y, z, 0) for one joint, or a LaneVector3 for four
  * joints at once; the products below are written once for both. */
template <class Vector3>
struct Rotation3
{
    Vector3 c[3];
};

/** The unit vector along an axis, for one joint or for every lane. */
template <unsigned Axis, class Vector3>
OSGACTOR_INLINE Vector3 unitVector()
{
    constexpr double x = Axis == 0 ? 1.0 : 0.0, y = Axis == 1 ? 1.0 : 0.0, z = Axis == 2 ? 1.0 : 0.0;
    if constexpr (std::is_same_v<Vector3, LaneVector3>)
        return LaneVector3{Column{x, x, x, x}, Column{y, y, y, y}, Column{z, z, z, z}};
    else
        return Column{x, y, z, 0.0};
}

/** m = R_Axis(angle), from the angle's sine and cosine (a double, or a Column of one per lane). Column I, row J of
  * an axis rotation: X mixes (Y, Z), Y mixes (Z, X), Z mixes (X, Y). The axis is a template argument so every index
  * is a constant, and the zeros and ones of the unit vectors fold away. */
template <unsigned Axis, class Vector3, class Scalar>
OSGACTOR_INLINE void setAxisRotation(Rotation3<Vector3>& m, Scalar s, Scalar c)
{
    constexpr unsigned i = (Axis + 1) % 3, j = (Axis + 2) % 3;
    m.c[Axis] = unitVector<Axis, Vector3>();
    m.c[i] = c * unitVector<i, Vector3>() + s * unitVector<j, Vector3>();
    m.c[j] = -s * unitVector<i, Vector3>() + c * unitVector<j, Vector3>();
}

/** m = m * R_Axis(angle): right-multiplying by an axis rotation mixes two columns only. */
template <unsigned Axis, class Vector3, class Scalar>
OSGACTOR_INLINE void postRotateAxis(Rotation3<Vector3>& m, Scalar s, Scalar c)
{
    constexpr unsigned i = (Axis + 1) % 3, j = (Axis + 2) % 3;
    const Vector3 ci = m.c[i], cj = m.c[j];
    m.c[i] = c * ci + s * cj;
    m.c[j] = -s * ci + c * cj;
}

/** The four columns of an affine matrix. */
struct AffineColumns
{
    Column c[4];
};

OSGACTOR_INLINE AffineColumns loadAffine(const double* m)
{
    return {{loadColumn(m), loadColumn(m + 4), loadColumn(m + 8), loadColumn(m + 12)}};
}

OSGACTOR_INLINE void storeAffine(double* m, const AffineColumns& a)
{
    for (unsigned col = 0; col < 4; ++col) storeColumn(m + 4 * col, a.c[col]);
}

/** a * b for affine matrices, a as columns, b stored as dmat4 (16 doubles, column-major; bottom row 0 0 0 1).
  * Column by column: out's column k is a's columns weighted by b's column k, whose bottom element is known (0, or 1
  * for the translation), so each column costs three broadcasts and three multiply-adds. */
OSGACTOR_INLINE AffineColumns multiplyAffineColumns(const AffineColumns& a, const double* __restrict b)
{
    AffineColumns out;
    for (unsigned col = 0; col < 3; ++col)
        out.c[col] = combineColumns(a.c[0], a.c[1], a.c[2], b[4 * col], b[4 * col + 1], b[4 * col + 2]);
    out.c[3] = combineColumns(a.c[0], a.c[1], a.c[2], b[12], b[13], b[14]) + a.c[3];
    return out;
}

/** out = a * b for affine matrices stored as dmat4 (16 doubles, column-major); out may not alias a or b. */
OSGACTOR_INLINE void multiplyAffineInto(const double* __restrict a, const double* __restrict b,
                                        double* __restrict out)
{
    storeAffine(out, multiplyAffineColumns(loadAffine(a), b));
}

/** The axes of a rotation sequence (see rotationSequenceOf), decoded at compile time. */
template <unsigned Sequence>
struct SequenceAxes
{
    static constexpr unsigned count = Sequence == 0 ? 0 : Sequence < 4 ? 1 : Sequence < 13 ? 2 : 3;
    static constexpr unsigned code = count == 1 ? Sequence - 1 : count == 2 ? Sequence - 4 : Sequence - 13;
    static constexpr unsigned first = count == 1 ? code : count == 2 ? code / 3 : code / 9;
    static constexpr unsigned second = count == 2 ? code % 3 : (code / 3) % 3;
    static constexpr unsigned third = code % 3;
};

/** Calls visit(std::integral_constant<unsigned, S>()) for the rotation sequence S = sequence: one jump to code
  * specialised for it. */
template <class Visitor>
OSGACTOR_INLINE void withRotationSequence(unsigned sequence, Visitor&& visit)
{
    switch (sequence)
    {
#define OSGACTOR_SEQUENCE(S)                                                                                           \
    case S: visit(std::integral_constant<unsigned, S>()); return;
#define OSGACTOR_SEQUENCES_FROM(S)                                                                                     \
    OSGACTOR_SEQUENCE(S) OSGACTOR_SEQUENCE(S + 1) OSGACTOR_SEQUENCE(S + 2) OSGACTOR_SEQUENCE(S + 3)                   \
    OSGACTOR_SEQUENCE(S + 4) OSGACTOR_SEQUENCE(S + 5) OSGACTOR_SEQUENCE(S + 6) OSGACTOR_SEQUENCE(S + 7)
        OSGACTOR_SEQUENCES_FROM(0)
        OSGACTOR_SEQUENCES_FROM(8)
        OSGACTOR_SEQUENCES_FROM(16)
        OSGACTOR_SEQUENCES_FROM(24)
        OSGACTOR_SEQUENCES_FROM(32)
#undef OSGACTOR_SEQUENCES_FROM
#undef OSGACTOR_SEQUENCE
    }
    static_assert(kNumRotationSequences == 40, "one case per rotation sequence above");
}

/** A joint's sines and cosines in product order. */
struct TrigInOrder
{
    double sines[4];
    double cosines[4];
    /** Computed together, one column for up to three angles; right where every angle is within the fast range,
      * which guard checks. */
    static OSGACTOR_INLINE TrigInOrder inFastRange(const JointKinematics& k, const double* dofs,
                                                   FastSinCosRangeGuard& guard)
    {
        double angles[4] = {0.0, 0.0, 0.0, 0.0};
        for (unsigned r = 0; r < k.numRotations; ++r) angles[r] = dofs[k.rotationDof[r]];
        const Column x = loadColumn(angles);
        guard.check(x);
        Column s, c;
        sinCosColumnInFastRange(x, s, c);
        TrigInOrder trig;
        storeColumn(trig.sines, s);
        storeColumn(trig.cosines, c);
        return trig;
    }
    /** From the library's functions, for any finite angle. */
    static TrigInOrder exact(const JointKinematics& k, const double* dofs)
    {
        TrigInOrder trig;
        for (unsigned r = 0; r < k.numRotations; ++r)
        {
            trig.sines[r] = std::sin(dofs[k.rotationDof[r]]);
            trig.cosines[r] = std::cos(dofs[k.rotationDof[r]]);
        }
        return trig;
    }
    double sine(unsigned r) const { return sines[r]; }
    double cosine(unsigned r) const { return cosines[r]; }
};

/** A batch's sines and cosines in product order (Count rotations), one joint per lane: each rotation's angles are
  * gathered from the DOF vector into one column. Right where every angle is within the fast range, which guard
  * checks. */
template <unsigned Count>
struct TrigByLane
{
    Column sines[Count > 0 ? Count : 1];
    Column cosines[Count > 0 ? Count : 1];
    OSGACTOR_INLINE TrigByLane(const JointBatch& batch, const double* dofs, FastSinCosRangeGuard& guard)
    {
        for (unsigned r = 0; r < Count; ++r)
        {
            const std::uint32_t* dof = batch.angleDofs[r];
            const Column angles = {dofs[dof[0]], dofs[dof[1]], dofs[dof[2]], dofs[dof[3]]};
            guard.check(angles);
            sinCosColumnInFastRange(angles, sines[r], cosines[r]);
        }
    }
    OSGACTOR_INLINE Column sine(unsigned r) const { return sines[r]; }
    OSGACTOR_INLINE Column cosine(unsigned r) const { return cosines[r]; }
};

/** m = R_a1 * R_a2 * R_a3 for a sequence known at compile time: every index is a constant, and the identity's
  * zeros and ones fold away (this file is built with -ffinite-math-only -fno-signed-zeros, which lets 0 * x fold;
  * FK sees finite values only, since the pose refuses NaN and infinity and definitions are validated). */
template <unsigned Sequence, class Vector3, class Trig>
OSGACTOR_INLINE void composeRotation(Rotation3<Vector3>& m, const Trig& trig)
{
    using Axes = SequenceAxes<Sequence>;
    if constexpr (Axes::count == 0)
        m = Rotation3<Vector3>{{unitVector<0, Vector3>(), unitVector<1, Vector3>(), unitVector<2, Vector3>()}};
    else
    {
        setAxisRotation<Axes::first>(m, trig.sine(0), trig.cosine(0));
        if constexpr (Axes::count >= 2) postRotateAxis<Axes::second>(m, trig.sine(1), trig.cosine(1));
        if constexpr (Axes::count >= 3) postRotateAxis<Axes::third>(m, trig.sine(2), trig.cosine(2));
    }
}

/** Writes skl_m of one joint (see computeJointMatrix) from the sines and cosines of its rotations; Sequence is the
  * joint's rotation sequence. */
template <unsigned Sequence>
OSGACTOR_INLINE void buildJointMatrix(const JointKinematics& k, const double* dofs, const TrigInOrder& trig,
                                      double* __restrict out)
{
    Rotation3<Column> rotation;
    composeRotation<Sequence>(rotation, trig);

    // The translation DOFs, slid along the rotated axes (the paper) or in the offset frame (mocap).
    Column slide = {0.0, 0.0, 0.0, 0.0};
    if (k.hasTranslation)
    {
        double t[3];
        for (unsigned axis = 0; axis < 3; ++axis)
            t[axis] = k.translationDof[axis] >= 0 ? dofs[k.translationDof[axis]] : 0.0;
        slide = k.translationMode == TranslationMode::AfterRotation
                    ? combineColumns(rotation.c[0], rotation.c[1], rotation.c[2], t[0], t[1], t[2])
                    : Column{t[0], t[1], t[2], 0.0};
    }

    // skl_m = offset_m * [rotation | slide]. Columns of the rotation end in 0, the offset's translation in 1.
    const double* offset = &k.offset[0][0];
    if (k.offsetIsTranslation)
    {
        for (unsigned col = 0; col < 3; ++col) storeColumn(out + 4 * col, rotation.c[col]);
        storeColumn(out + 12, slide + loadColumn(offset + 12));
        return;
    }
    const Column o0 = loadColumn(offset), o1 = loadColumn(offset + 4), o2 = loadColumn(offset + 8);
    for (unsigned col = 0; col < 3; ++col)
    {
        const Column r = rotation.c[col];
        storeColumn(out + 4 * col, combineColumns(o0, o1, o2, r[0], r[1], r[2]));
    }
    storeColumn(out + 12, combineColumns(o0, o1, o2, slide[0], slide[1], slide[2]) + loadColumn(offset + 12));
}

/** buildJointMatrix for the joint's own rotation sequence. */
OSGACTOR_INLINE void buildJointMatrixDispatched(const JointKinematics& k, const double* dofs, const TrigInOrder& trig,
                                                double* __restrict out)
{
    withRotationSequence(k.rotationSequence, [&](auto sequence) OSGACTOR_INLINE_LAMBDA {
        buildJointMatrix<decltype(sequence)::value>(k, dofs, trig, out);
    });
}

/** The four joints' own columns from one LaneVector3: result[l] = (v.x[l], v.y[l], v.z[l], 0), a 4x4 transpose
  * with a zero row. Shuffle indices count the lanes of both arguments, the second's from 4. */
OSGACTOR_INLINE void transposeLanes(const LaneVector3& v, Column result[JointBatch::kWidth])
{
    const Column zero = {0.0, 0.0, 0.0, 0.0};
    const Column xy02 = __builtin_shufflevector(v.x, v.y, 0, 4, 2, 6);
    const Column xy13 = __builtin_shufflevector(v.x, v.y, 1, 5, 3, 7);
    const Column z02 = __builtin_shufflevector(v.z, zero, 0, 4, 2, 6);
    const Column z13 = __builtin_shufflevector(v.z, zero, 1, 5, 3, 7);
    result[0] = __builtin_shufflevector(xy02, z02, 0, 1, 4, 5);
    result[1] = __builtin_shufflevector(xy13, z13, 0, 1, 4, 5);
    result[2] = __builtin_shufflevector(xy02, z02, 2, 3, 6, 7);
    result[3] = __builtin_shufflevector(xy13, z13, 2, 3, 6, 7);
}

/** Writes skl_m of the batch's joints whose bit is set in lanes (see JointBatch): the rotations of all four
  * composed at once, one per lane, then turned into each joint's columns. Their offsets are translations and they
  * have no translation DOF, so the last column is the offset's. */
template <unsigned Sequence>
OSGACTOR_INLINE void buildBatchMatrices(const JointBatch& batch, const JointKinematics* kinematics, const double* dofs,
                                        double* const* local, unsigned lanes, FastSinCosRangeGuard& guard)
{
    Rotation3<LaneVector3> rotation;
    composeRotation<Sequence>(rotation, TrigByLane<SequenceAxes<Sequence>::count>(batch, dofs, guard));
    Column columns[3][JointBatch::kWidth];
    for (unsigned col = 0; col < 3; ++col) transposeLanes(rotation.c[col], columns[col]);
    for (unsigned lane = 0; lane < JointBatch::kWidth; ++lane)
    {
        if ((lanes >> lane & 1u) == 0) continue;
        const std::uint32_t joint = batch.joints[lane];
        double* const out = local[joint];
        for (unsigned col = 0; col < 3; ++col) storeColumn(out + 4 * col, columns[col][lane]);
        storeColumn(out + 12, loadColumn(&kinematics[joint].offset[3][0]));
    }
}

/** Whether every one of count flags is non-zero, eight at a time: a word w has a zero byte exactly when
  * (w - 0x0101...01) & ~w & 0x8080...80 is non-zero. The last word overlaps the one before rather than leaving a
  * tail of single bytes (a byte loop over a skeleton's 31 flags was 4% of the pose's instructions). */
OSGACTOR_INLINE bool allSet(const std::uint8_t* flags, unsigned count)
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

/** The flags of a joint whose local matrix was just rebuilt. */
OSGACTOR_INLINE void markRebuilt(std::uint8_t* jointDirty, std::uint8_t* localChanged, std::uint8_t* modelStale,
                                 unsigned joint)
{
    jointDirty[joint] = 0;
    localChanged[joint] = 1;
    modelStale[joint] = 1;
}

unsigned buildLocalMatricesExactly(const ForwardKinematicsJob& job);

/** Step 1 of the job: the local matrices of the dirty joints, batch by batch (see JointBatch), then the joints built
  * one at a time. A batch with a single dirty joint builds it on its own, which is cheaper than four lanes. Returns
  * how many local matrices it rebuilt. A pose with an angle beyond the fast sine and cosine's range goes to
  * buildLocalMatricesExactly. Every buffer is read into a local first: the flags are bytes, which may alias
  * anything, so fields of the job would be reloaded after each flag store. */
OSGACTOR_HOT_PATH unsigned buildLocalMatrices(const ForwardKinematicsJob& job)
{
    const JointBatchPlan& plan = job.definition->getJointBatches();
    const JointKinematics* const kinematics = job.definition->getAllKinematics().data();
    const unsigned numJoints = job.definition->getNumJoints();
    const double* const dofs = job.dofs;
    std::uint8_t* const jointDirty = job.jointDirty;
    std::uint8_t* const localChanged = job.localChanged;
    std::uint8_t* const modelStale = job.modelStale;
    double* const* const local = job.local;
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

    if (allSet(jointDirty, numJoints))
    {
        // A clip playing moves every joint: no flag to test per joint, and the flags set in three sweeps after. The
        // angles' range is checked as they are gathered; no flag has changed yet if a redo is needed.
        for (const JointBatch& batch : plan.batches) buildBatch(batch, (1u << batch.numJoints) - 1u);
        for (const std::uint32_t joint : plan.singleJoints) buildOne(joint);
        if (!guard.passed()) return buildLocalMatricesExactly(job);
        std::memset(jointDirty, 0, numJoints);
        std::memset(localChanged, 1, numJoints);
        std::memset(modelStale, 1, numJoints);
        return numJoints;
    }

    // Some joints: flags change as joints are built, so the range is checked first, over the whole DOF vector
    // (translations too: cheaper than picking the angles out).
    if (!withinFastSinCosRange(dofs, job.definition->getNumDofs())) return buildLocalMatricesExactly(job);
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
            markRebuilt(jointDirty, localChanged, modelStale, joint);
            ++numRebuilt;
            continue;
        }
        buildBatch(batch, lanes);
        for (unsigned lane = 0; lane < JointBatch::kWidth; ++lane)
            if (lanes >> lane & 1u) markRebuilt(jointDirty, localChanged, modelStale, batch.joints[lane]);
        numRebuilt += static_cast<unsigned>(__builtin_popcount(lanes));
    }
    for (const std::uint32_t joint : plan.singleJoints)
        if (jointDirty[joint])
        {
            buildOne(joint);
            markRebuilt(jointDirty, localChanged, modelStale, joint);
            ++numRebuilt;
        }
    return numRebuilt;
}

/** The model matrix of joint j from its parent's and its local one. */
OSGACTOR_INLINE void composeModelMatrix(const int* parents, double* const* local, glm::dmat4* model, unsigned j)
{
    const int parent = parents[j];
    if (parent >= 0)
        multiplyAffineInto(&model[parent][0][0], local[j], &model[j][0][0]);
    else
        std::memcpy(&model[j][0][0], local[j], sizeof(glm::dmat4));
}

/** Step 2 of the job: one pass over the joints, parents first, composing the model matrix of every joint whose
  * local matrix or any ancestor's was rebuilt. */
OSGACTOR_HOT_PATH void composeModelMatrices(const ForwardKinematicsJob& job)
{
    const unsigned numJoints = job.definition->getNumJoints();
    const int* const parents = job.definition->getParents().data();
    std::uint8_t* const modelStale = job.modelStale;
    std::uint8_t* const modelChanged = job.modelChanged;
    double* const* const local = job.local;
    glm::dmat4* const model = job.model;
    if (allSet(modelStale, numJoints))
    {
        // Joint after joint down a chain (the parent the joint just before), the parent's columns are still in
        // registers: reading them back from the store just made would add the store-to-load latency to every link
        // of the chain, which is what bounds this loop.
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
        std::memset(modelStale, 0, numJoints);
        std::memset(modelChanged, 1, numJoints);
        return;
    }
    for (unsigned j = 0; j < numJoints; ++j)
    {
        const int parent = parents[j];
        // Parents come first, so modelChanged[parent] is already final for this run.
        const bool moved = modelStale[j] || (parent >= 0 && modelChanged[parent]);
        modelChanged[j] = moved ? 1 : 0;
        if (!moved) continue;
        modelStale[j] = 0;
        composeModelMatrix(parents, local, model, j);
    }
}

/** Step 1 for a pose with an angle beyond the fast sine and cosine's range (more than 1e6 radians): joint by
  * joint, through the library's functions. */
unsigned buildLocalMatricesExactly(const ForwardKinematicsJob& job)
{
    unsigned numRebuilt = 0;
    for (unsigned joint = 0; joint < job.definition->getNumJoints(); ++joint)
    {
        if (!job.jointDirty[joint]) continue;
        const JointKinematics& k = job.definition->getKinematics(joint);
        buildJointMatrixDispatched(k, job.dofs, TrigInOrder::exact(k, job.dofs), job.local[joint]);
        markRebuilt(job.jointDirty, job.localChanged, job.modelStale, joint);
        ++numRebuilt;
    }
    return numRebuilt;
}

} // namespace

glm::dmat4 multiplyAffine(const glm::dmat4& a, const glm::dmat4& b)
{
    glm::dmat4 result;
    multiplyAffineInto(&a[0][0], &b[0][0], &result[0][0]);
    return result;
}

glm::dmat4 computeJointMatrix(const JointKinematics& k, const double* dofs)
{
    glm::dmat4 result;
    buildJointMatrixDispatched(k, dofs, TrigInOrder::exact(k, dofs), &result[0][0]);
    return result;
}

bool ForwardKinematicsJob::validate() const
{
    if (!definition || !jointDirty || !local || !model || !localChanged || !modelStale || !modelChanged) return false;
    return dofs != nullptr || definition->getNumDofs() == 0;
}

bool ForwardKinematicsJob::run()
{
    numRecomputed = 0;
    if (!validate()) return false;
    if (rebuildLocal)
        numRecomputed = buildLocalMatrices(*this);
    if (computeModel) composeModelMatrices(*this);
    return true;
}

} // namespace osgActor
