// The per-frame hot path. Matrices are glm::dmat4 in memory (column-major, 16 doubles) but are handled here as raw
// affine arrays: the bottom row of every joint matrix is (0 0 0 1), so a product is a 3x3 rotation product plus a
// translation, not a full 4x4 product. This file is compiled with -O3 and its loop is built twice (AVX2+FMA and
// the x86-64 baseline), the right one chosen when the library is loaded.
#include <osgActor/core/ForwardKinematicsJob>
#include <osgActor/core/SinCos>

#include "HotPath.h"

#include <cmath>
#include <cstring>

namespace osgActor {

namespace {

#define OSGACTOR_INLINE inline __attribute__((always_inline))

// Columns pass by value between always-inline functions only, so the warning that a 32-byte vector argument changes
// the ABI without AVX (the baseline clone) concerns no real call.
#pragma GCC diagnostic ignored "-Wpsabi"

/** Four doubles as one value: a matrix column. GCC's vector extension, so the same code is 4 wide in the AVX2 clone
  * and two SSE2 halves in the baseline one. */
typedef double Column __attribute__((vector_size(32)));
/** The same at double alignment, for loads and stores of matrices wherever they are (a node's matrix). */
typedef double UnalignedColumn __attribute__((vector_size(32), aligned(8)));

OSGACTOR_INLINE Column loadColumn(const double* p) { return *reinterpret_cast<const UnalignedColumn*>(p); }
OSGACTOR_INLINE void storeColumn(double* p, Column c) { *reinterpret_cast<UnalignedColumn*>(p) = c; }

/** x a0 + y a1 + z a2: a point or direction (x, y, z) taken through the three axis columns of a matrix. Every product
  * of matrices here is columns of this. */
OSGACTOR_INLINE Column combineColumns(Column a0, Column a1, Column a2, double x, double y, double z)
{
    return a0 * x + a1 * y + a2 * z;
}

/** A 3x3 rotation as three columns (x, y, z, 0): each column is one vector. */
struct Rotation3
{
    Column c[3];
};

/** The unit column along an axis. */
template <unsigned Axis>
OSGACTOR_INLINE Column unitColumn()
{
    return Column{Axis == 0 ? 1.0 : 0.0, Axis == 1 ? 1.0 : 0.0, Axis == 2 ? 1.0 : 0.0, 0.0};
}

/** m = R_Axis(angle), from the angle's sine and cosine. Column I, row J of an axis rotation: X mixes (Y, Z),
  * Y mixes (Z, X), Z mixes (X, Y). The axis is a template argument so every index is a constant. */
template <unsigned Axis>
OSGACTOR_INLINE void setAxisRotation(Rotation3& m, double s, double c)
{
    constexpr unsigned i = (Axis + 1) % 3, j = (Axis + 2) % 3;
    m.c[Axis] = unitColumn<Axis>();
    m.c[i] = c * unitColumn<i>() + s * unitColumn<j>();
    m.c[j] = -s * unitColumn<i>() + c * unitColumn<j>();
}

/** m = m * R_Axis(angle): right-multiplying by an axis rotation mixes two columns only. */
template <unsigned Axis>
OSGACTOR_INLINE void postRotateAxis(Rotation3& m, double s, double c)
{
    constexpr unsigned i = (Axis + 1) % 3, j = (Axis + 2) % 3;
    const Column ci = m.c[i], cj = m.c[j];
    m.c[i] = c * ci + s * cj;
    m.c[j] = -s * ci + c * cj;
}

/** out = a * b for affine matrices stored as dmat4 (16 doubles, column-major; bottom rows 0 0 0 1); out may not
  * alias a or b. Column by column: out's column k is a's columns weighted by b's column k, whose bottom element is
  * known (0, or 1 for the translation), so each column costs three broadcasts and three multiply-adds. */
OSGACTOR_INLINE void multiplyAffineInto(const double* __restrict a, const double* __restrict b,
                                        double* __restrict out)
{
    const Column a0 = loadColumn(a), a1 = loadColumn(a + 4), a2 = loadColumn(a + 8), a3 = loadColumn(a + 12);
    for (unsigned col = 0; col < 3; ++col)
        storeColumn(out + 4 * col, combineColumns(a0, a1, a2, b[4 * col], b[4 * col + 1], b[4 * col + 2]));
    storeColumn(out + 12, combineColumns(a0, a1, a2, b[12], b[13], b[14]) + a3);
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

/** A joint's sines and cosines read from arrays indexed by DOF (the per-frame path: one batch for the whole pose). */
struct TrigByDof
{
    const std::uint32_t* rotationDof;
    const double* sines;
    const double* cosines;
    double sine(unsigned r) const { return sines[rotationDof[r]]; }
    double cosine(unsigned r) const { return cosines[rotationDof[r]]; }
};

/** A joint's sines and cosines in product order (a single joint computed on its own). */
struct TrigInOrder
{
    double sines[3];
    double cosines[3];
    double sine(unsigned r) const { return sines[r]; }
    double cosine(unsigned r) const { return cosines[r]; }
};

/** m = R_a1 * R_a2 * R_a3 for a sequence known at compile time: every index is a constant, and the identity's
  * zeros and ones fold away (this file is built with -ffinite-math-only -fno-signed-zeros, which lets 0 * x fold;
  * FK sees finite values only, since the pose refuses NaN and infinity and definitions are validated). */
template <unsigned Sequence, class Trig>
OSGACTOR_INLINE void composeRotation(Rotation3& m, const Trig& trig)
{
    using Axes = SequenceAxes<Sequence>;
    if constexpr (Axes::count == 0)
        setAxisRotation<0>(m, 0.0, 1.0);
    else
    {
        setAxisRotation<Axes::first>(m, trig.sine(0), trig.cosine(0));
        if constexpr (Axes::count >= 2) postRotateAxis<Axes::second>(m, trig.sine(1), trig.cosine(1));
        if constexpr (Axes::count >= 3) postRotateAxis<Axes::third>(m, trig.sine(2), trig.cosine(2));
    }
}

/** Writes skl_m of one joint (see computeJointMatrix) from the sines and cosines of its active rotations;
  * Sequence is the joint's rotation sequence. */
template <unsigned Sequence, class Trig>
OSGACTOR_INLINE void buildJointMatrix(const JointKinematics& k, const double* dofs, const Trig& trig,
                                      double* __restrict out)
{
    Rotation3 rotation;
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

/** buildJointMatrix for the joint's own rotation sequence: one jump to code specialised for it. */
template <class Trig>
OSGACTOR_INLINE void buildJointMatrixDispatched(const JointKinematics& k, const double* dofs, const Trig& trig,
                                                double* __restrict out)
{
    switch (k.rotationSequence)
    {
#define OSGACTOR_SEQUENCE(S)                                                                                           \
    case S: buildJointMatrix<S>(k, dofs, trig, out); return;
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

/** Step 2 of the job: one pass over the joints, parents first. Returns how many local matrices it rebuilt. Every
  * buffer is read into a local first: the flags are bytes, which may alias anything, so fields of the job would be
  * reloaded after each flag store. */
OSGACTOR_HOT_PATH unsigned computeMatrices(const ForwardKinematicsJob& job, const double* sines, const double* cosines)
{
    const unsigned numJoints = job.definition->getNumJoints();
    const JointKinematics* const kinematics = job.definition->getAllKinematics().data();
    const int* const parents = job.definition->getParents().data();
    const double* const dofs = job.dofs;
    std::uint8_t* const jointDirty = job.jointDirty;
    std::uint8_t* const localChanged = job.localChanged;
    std::uint8_t* const modelStale = job.modelStale;
    std::uint8_t* const modelChanged = job.modelChanged;
    double* const* const local = job.local;
    glm::dmat4* const model = job.model;
    const bool rebuildLocal = job.rebuildLocal;
    const bool computeModel = job.computeModel;
    unsigned numRecomputed = 0;
    for (unsigned j = 0; j < numJoints; ++j)
    {
        if (rebuildLocal && jointDirty[j])
        {
            const JointKinematics& k = kinematics[j];
            buildJointMatrixDispatched(k, dofs, TrigByDof{k.rotationDof, sines, cosines}, local[j]);
            jointDirty[j] = 0;
            localChanged[j] = 1;
            modelStale[j] = 1;
            ++numRecomputed;
        }
        if (!computeModel) continue;
        const int parent = parents[j];
        // Parents come first, so modelChanged[parent] is already final for this run.
        const bool moved = modelStale[j] || (parent >= 0 && modelChanged[parent]);
        modelChanged[j] = moved ? 1 : 0;
        if (!moved) continue;
        modelStale[j] = 0;
        if (parent >= 0)
            multiplyAffineInto(&model[parent][0][0], local[j], &model[j][0][0]);
        else
            std::memcpy(&model[j][0][0], local[j], sizeof(glm::dmat4));
    }
    return numRecomputed;
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
    TrigInOrder trig;
    for (unsigned r = 0; r < k.numRotations; ++r)
    {
        trig.sines[r] = std::sin(dofs[k.rotationDof[r]]);
        trig.cosines[r] = std::cos(dofs[k.rotationDof[r]]);
    }
    glm::dmat4 result;
    buildJointMatrixDispatched(k, dofs, trig, &result[0][0]);
    return result;
}

bool ForwardKinematicsJob::validate() const
{
    if (!definition || !jointDirty || !local || !model || !localChanged || !modelStale || !modelChanged) return false;
    return (dofs != nullptr && trigScratch != nullptr) || definition->getNumDofs() == 0;
}

bool ForwardKinematicsJob::run()
{
    numRecomputed = 0;
    if (!validate()) return false;
    const unsigned numJoints = definition->getNumJoints();
    const JointKinematics* kinematics = definition->getAllKinematics().data();

    // 1. The sines and cosines of the dirty joints' angles in one batch, indexed by DOF. When most joints are dirty
    //    (a clip playing) the batch is the DOF vector itself: no gathering, and the few translations cost a few
    //    wasted lanes. Otherwise the dirty joints' angles are gathered, and the results scattered back.
    const unsigned numDofs = definition->getNumDofs();
    double* sines = trigScratch;
    double* cosines = trigScratch + numDofs;
    if (rebuildLocal && numDofs > 0)
    {
        unsigned numDirty = 0;
        for (unsigned j = 0; j < numJoints; ++j) numDirty += jointDirty[j] != 0 ? 1u : 0u;
        if (2 * numDirty >= numJoints)
            sinCos(dofs, sines, cosines, numDofs);
        else
        {
            double* angles = trigScratch + 2 * numDofs;
            double* gatheredSines = angles + numDofs;
            double* gatheredCosines = gatheredSines + numDofs;
            unsigned numAngles = 0;
            for (unsigned j = 0; j < numJoints; ++j)
                if (jointDirty[j])
                    for (unsigned r = 0; r < kinematics[j].numRotations; ++r)
                        angles[numAngles++] = dofs[kinematics[j].rotationDof[r]];
            sinCos(angles, gatheredSines, gatheredCosines, numAngles);
            numAngles = 0;
            for (unsigned j = 0; j < numJoints; ++j)
                if (jointDirty[j])
                    for (unsigned r = 0; r < kinematics[j].numRotations; ++r, ++numAngles)
                    {
                        sines[kinematics[j].rotationDof[r]] = gatheredSines[numAngles];
                        cosines[kinematics[j].rotationDof[r]] = gatheredCosines[numAngles];
                    }
        }
    }

    // 2. Local matrices of dirty joints, model matrices below any change.
    numRecomputed = computeMatrices(*this, sines, cosines);
    return true;
}

} // namespace osgActor
