// Internal to the library (not installed): the fits of fitJointRotationDofs (JointRotationFit) for joints with one or
// two rotations (a knee, an ankle), four joints at once, one per vector lane (../Column.h), for RetargetJob: the angle
// about one axis, or the two about two axes, whose rotation is nearest the joint's local rotation in least squares,
// each turned to the whole turn nearest the previous frame's value, and their sines and cosines. A lane whose joint
// needs more (an angle beyond its limits, to be clamped) is reported, and left to the scalar fit.
#ifndef OSGACTOR_CORE_RETARGET_AXISLANES_H
#define OSGACTOR_CORE_RETARGET_AXISLANES_H 1

#include "../detail/SinCosColumn.h"
#include "EulerLanes.h"

namespace osgActor {
namespace retarget_detail {

/** What fitAxisLanes gives back: per rotation in product order and lane, the angle (radians) and its sine and cosine,
  * and per lane whether its joint is fitted (every angle within its limits). */
struct AxisLanesFit
{
    Column angles[2], sines[2], cosines[2];
    LaneMask fitted;
};

/** The fit of a batch's joints (see RetargetAxisBatch), each joint's local rotation given as columns of four (12
  * doubles, local[lane]). With m' the local rotation in the lane's axes (m'(r, c) = m(a_r, a_c)), the same arithmetic
  * as the scalar fit's: for one rotation, the arctangent of the part of m' about a0; for two, B's first singular
  * vectors (see nearestTwoAxes in JointRotationFit.cpp), from the products of the quaternion's components that are
  * linear in m'. */
OSGACTOR_INLINE AxisLanesFit fitAxisLanes(const RetargetAxisBatch& batch, const double* const local[4],
                                          const double* dofs)
{
    const auto m = [&](unsigned row, unsigned column) OSGACTOR_INLINE_LAMBDA {
        const std::uint8_t* at = batch.element[row][column];
        return Column{local[0][at[0]], local[1][at[1]], local[2][at[2]], local[3][at[3]]};
    };
    LaneMask invalid = {0, 0, 0, 0};
    AxisLanesFit fit;
    if (batch.numRotations == 1)
        fit.angles[0] = arctangent2Lanes(m(2, 1) - m(1, 2), m(1, 1) + m(2, 2), invalid);
    else
    {
        const Column sign = loadColumn(batch.parity);
        const Column m00 = m(0, 0), m11 = m(1, 1), m22 = m(2, 2);
        const Column trace = m00 + m11 + m22;
        const auto squared = [&](Column diagonal) OSGACTOR_INLINE_LAMBDA { // a component of the quaternion, squared
            return 0.25 * (1.0 + 2.0 * diagonal - trace);
        };
        const auto timesW = [&](unsigned r) OSGACTOR_INLINE_LAMBDA { // w times a component, in the lane's axes
            const unsigned i = (r + 1u) % 3u, k = (r + 2u) % 3u;
            return 0.25 * (m(k, i) - m(i, k));
        };
        const auto product = [&](unsigned r, unsigned c) OSGACTOR_INLINE_LAMBDA { return 0.25 * (m(r, c) + m(c, r)); };
        // B's elements a = w, b = q_a1, c = q_a0, d = sign q_a2, multiplied in pairs (w q_a turns sign with the order).
        const Column aa = 0.25 * (1.0 + trace), bb = squared(m11), cc = squared(m00), dd = squared(m22);
        const Column ab = sign * timesW(1), ac = sign * timesW(0), ad = timesW(2);
        const Column bc = product(0, 1), bd = sign * product(1, 2), cd = sign * product(0, 2);
        const Column half = 0.5 * ((aa + cc) - (bb + dd)), offDiagonal = ab + cd;
        const Column squaredRadius = half * half + offDiagonal * offDiagonal;
        const Column radius = {std::sqrt(squaredRadius[0]), std::sqrt(squaredRadius[1]), std::sqrt(squaredRadius[2]),
                               std::sqrt(squaredRadius[3])};
        const LaneMask distinct = radius > 1e-15;
        const Column c1 = select(distinct, half / radius, broadcast(1.0));
        const Column s1 = select(distinct, offDiagonal / radius, broadcast(0.0));
        const Column cosSquared = 0.5 * (1.0 + c1), sinSquared = 0.5 * (1.0 - c1);
        const Column u0u0 = aa * cosSquared + ab * s1 + bb * sinSquared;
        const Column u1u1 = cc * cosSquared + cd * s1 + dd * sinSquared;
        const Column u0u1 = ac * cosSquared + 0.5 * (ad + bc) * s1 + bd * sinSquared;
        fit.angles[0] = arctangent2Lanes(2.0 * u0u1, u0u0 - u1u1, invalid);
        fit.angles[1] = arctangent2Lanes(s1, c1, invalid);
    }
    LaneMask within = ~invalid;
    for (unsigned r = 0; r < batch.numRotations; ++r)
    {
        fit.angles[r] = turnNearLanes(fit.angles[r], gatherLanes(dofs, batch.dof[r]), loadColumn(batch.min[r]),
                                      loadColumn(batch.max[r]), within);
        sinCosColumn(fit.angles[r], fit.sines[r], fit.cosines[r]);
    }
    fit.fitted = within;
    return fit;
}

} // namespace retarget_detail
} // namespace osgActor

#endif
