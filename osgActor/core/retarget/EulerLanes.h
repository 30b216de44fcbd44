// Internal to the library (not installed): the Euler fit of fitJointRotationDofs (JointRotationFit) for four joints
// at once, one per vector lane (../Column.h), for RetargetJob: the decomposition's three arctangents and square root,
// and the turn of each angle to the whole turn nearest the previous frame's value, within the limits. In three steps
// (the arctangents' inputs, the arctangents, the turns), so the caller can run the long dependent chains of several
// batches' arctangents one after another, which the processor then overlaps. A lane whose joint needs more than that
// (gimbal lock, a limit, the second solution) is reported, and left to the scalar fit.
#ifndef OSGACTOR_CORE_RETARGET_EULERLANES_H
#define OSGACTOR_CORE_RETARGET_EULERLANES_H 1

#include <osgActor/core/retarget/RetargetRig>

#include "../detail/Column.h"
#include "RotationColumns.h"

#include <cmath>
#include <cstdint>
#include <limits>

namespace osgActor {
namespace retarget_detail {

/** A lane mask: all bits set in the lanes where a comparison holds. */
typedef ColumnSignedBits LaneMask;

OSGACTOR_INLINE Column broadcast(double x) { return Column{x, x, x, x}; }

OSGACTOR_INLINE Column select(LaneMask mask, Column yes, Column no) { return mask ? yes : no; }

/** Whether each lane's sign bit is set (-0.0 included, as std::signbit). */
OSGACTOR_INLINE LaneMask signBits(Column x) { return reinterpret_cast<ColumnSignedBits>(x) < 0; }

/** atan2(y, x), lane by lane, by arctangent2's method (core/ik/Arctangent: Cephes' reduction of |y| / |x| to
  * [0, tan(pi / 8)] and its rational approximation there), with two vector divisions for four arctangents. Lanes
  * where both are 0, or either is infinite or NaN, are set in invalid (their result is meaningless). */
OSGACTOR_INLINE Column arctangent2Lanes(Column y, Column x, LaneMask& invalid)
{
    constexpr double kPi = 3.14159265358979323846;
    constexpr double kPiOver2Low = 6.123233995736765886130e-17; // pi / 2 less its nearest double
    // Cephes' atan.c coefficients: atan(r) = r + r z P(z) / Q(z), z = r^2, Q monic.
    constexpr double kP[5] = {-8.750608600031904122785e-1, -1.615753718733365076637e1, -7.500855792314704667340e1,
                              -1.228866684490136173410e2, -6.485021904942025371773e1};
    constexpr double kQ[5] = {2.485846490142306297962e1, 1.650270098316988542046e2, 4.328810604912902668951e2,
                              4.853903996359136964868e2, 1.945506571482613964425e2};
    const Column b = absColumn(x), a = absColumn(y);
    const Column sum = a + b;
    invalid |= !(sum > 0.0 && sum < std::numeric_limits<double>::infinity());
    const LaneMask beyond = a > 2.41421356237309504880 * b; // beyond tan(3 pi / 8): pi / 2 - atan(b / a)
    const LaneMask middle = a > 0.66 * b;                   // from there: pi / 4 + atan((a - b) / (a + b))
    const Column zero = broadcast(0.0);
    const Column numerator = select(beyond, -b, select(middle, a - b, a));
    const Column denominator = select(beyond, a, select(middle, a + b, b));
    const Column base = select(beyond, broadcast(kPi / 2), select(middle, broadcast(kPi / 4), zero));
    const Column low = select(beyond, broadcast(kPiOver2Low), select(middle, broadcast(0.5 * kPiOver2Low), zero));
    const Column r = numerator / denominator;
    const Column z = r * r;
    Column p = broadcast(kP[0]), q = z + kQ[0];
    for (unsigned i = 1; i < 5; ++i)
    {
        p = p * z + kP[i];
        q = q * z + kQ[i];
    }
    Column angle = base + ((r * (z * p / q) + r) + low); // atan(a / b), in [0, pi / 2]
    angle = select(signBits(x), (kPi - angle) + 2.0 * kPiOver2Low, angle);
    return select(signBits(y), -angle, angle);
}

/** Each lane's value of a DOF vector, the DOFs given per lane. */
OSGACTOR_INLINE Column gatherLanes(const double* values, const std::uint32_t* index)
{
    return Column{values[index[0]], values[index[1]], values[index[2]], values[index[3]]};
}

/** angle turned, lane by lane, by the whole turns that bring it nearest reference (the previous frame's value);
  * within is cleared in the lanes where that lies outside [min, max] (or the turns are too many to count). */
OSGACTOR_INLINE Column turnNearLanes(Column angle, Column reference, Column min, Column max, LaneMask& within)
{
    constexpr double kTwoPi = 6.28318530717958647692;
    constexpr double kRoundingShift = 0x1.8p52; // adding and subtracting it rounds to an integer, ties to even
    const Column turns = (reference - angle) * (1.0 / kTwoPi);
    const Column rounded = (turns + kRoundingShift) - kRoundingShift;
    const Column turned = angle + kTwoPi * rounded;
    within &= absColumn(turns) < 0x1p50 && turned >= min && turned <= max;
    return turned;
}

/** The inputs of the Euler decomposition's three arctangents for a batch's joints, one joint per lane: angle r (in
  * product order) is atan2(y[r], x[r]); invalid is set in the lanes at gimbal lock (the scalar fit puts the free sum
  * in the last angle). */
struct EulerArctangents
{
    Column y[3], x[3];
    LaneMask invalid;
};

/** What a lane's joint's Euler decomposition reads, in its axes (i, j, k) in product order: columns a_0, a_1, a_2
  * (a_0 = i, ...) of its frame F (the parent's desired model rotation times the joint's offset rotation) and of its
  * desired model rotation D, each (x, y, z, 0). Its local rotation is m = F^T D, so m(a_r, a_c) = F_{a_r} . D_{a_c}:
  * the five elements the decomposition reads come straight from these registers, no local rotation stored and
  * gathered back. */
struct EulerLaneColumns
{
    Column frame[3], desired[3];
};

/** The arctangents' inputs of a batch's joints (see RetargetEulerBatch), from each lane's columns, for the
  * decomposition's first solution (the middle angle within [-pi/2, pi/2]). */
OSGACTOR_INLINE EulerArctangents eulerArctangents(const RetargetEulerBatch& batch,
                                                  const EulerLaneColumns (&lanes)[RetargetEulerBatch::kWidth])
{
    // Per axis place r: the x, y, z of F_{a_r} and of D_{a_r} across the lanes.
    Column fx[3], fy[3], fz[3], dx[3], dy[3], dz[3];
    for (unsigned r = 0; r < 3; ++r)
    {
        const Column f[4] = {lanes[0].frame[r], lanes[1].frame[r], lanes[2].frame[r], lanes[3].frame[r]};
        const Column d[4] = {lanes[0].desired[r], lanes[1].desired[r], lanes[2].desired[r], lanes[3].desired[r]};
        transposeToLanes(f, fx[r], fy[r], fz[r]);
        transposeToLanes(d, dx[r], dy[r], dz[r]);
    }
    // m(a_row, a_column), lane by lane, in the order of a product of rotations (x terms first).
    const auto element = [&](unsigned row, unsigned column) OSGACTOR_INLINE_LAMBDA {
        return fx[row] * dx[column] + fy[row] * dy[column] + fz[row] * dz[column];
    };
    const Column parity = loadColumn(batch.parity);
    const Column mii = element(0, 0), mij = element(0, 1);
    const Column squared = mii * mii + mij * mij;
    const Column cosMiddle = {std::sqrt(squared[0]), std::sqrt(squared[1]), std::sqrt(squared[2]),
                              std::sqrt(squared[3])};
    EulerArctangents in;
    in.invalid = !(cosMiddle > 1e-12);
    in.y[0] = -parity * element(1, 2);
    in.x[0] = element(2, 2);
    in.y[1] = parity * element(0, 2);
    in.x[1] = cosMiddle;
    in.y[2] = -parity * mij;
    in.x[2] = mii;
    return in;
}

/** What fitEulerLanes gives back: per lane, the three angles in product order, and whether the lane's joint is
  * fitted exactly. */
struct EulerLanesFit
{
    Column angles[3];
    LaneMask fitted;
};

/** The Euler fit of a batch's joints from their arctangents (angles, in product order, and invalid, as
  * eulerArctangents and arctangent2Lanes leave them): each angle turned by the whole turns that bring it nearest the
  * reference (dofs, the previous frame's values). A lane is fitted when that solution is what fitJointRotationDofs
  * takes: no gimbal lock, every angle within its limits, and the three within a quarter turn of the reference in all
  * (so the second solution is farther). */
OSGACTOR_INLINE EulerLanesFit fitEulerLanes(const RetargetEulerBatch& batch, const Column angles[3], LaneMask invalid,
                                            const double* dofs)
{
    EulerLanesFit fit;
    LaneMask within = ~invalid;
    Column distance = broadcast(0.0);
    for (unsigned r = 0; r < 3; ++r)
    {
        const Column reference = gatherLanes(dofs, batch.dof[r]);
        fit.angles[r] =
            turnNearLanes(angles[r], reference, loadColumn(batch.min[r]), loadColumn(batch.max[r]), within);
        distance += absColumn(fit.angles[r] - reference);
    }
    fit.fitted = within & (distance < 0.5 * 3.14159265358979323846);
    return fit;
}

} // namespace retarget_detail
} // namespace osgActor

#endif
