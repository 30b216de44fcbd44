// Internal to the library (not installed, NOT API): the arithmetic of one joint's skl_m (local space) and of a batch
// of four joints at once, one per vector lane: rotation sequences decoded at compile time, sines and cosines from
// SinCosColumn.h, the offset applied as columns. Used by LocalMatricesJob.cpp, compiled with -O3 and built twice
// (AVX2+FMA and the x86-64 baseline, see HotPath.h).
#ifndef OSGACTOR_CORE_DETAIL_JOINTMATRIXKERNEL_H
#define OSGACTOR_CORE_DETAIL_JOINTMATRIXKERNEL_H 1

#include <osgActor/core/ActorDefinition>

#include "AffineColumns.h"
#include "SinCosColumn.h"

#include <cmath>
#include <cstdint>
#include <type_traits>

namespace osgActor {

namespace joint_matrix_detail {

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

} // namespace joint_matrix_detail

} // namespace osgActor

#endif
