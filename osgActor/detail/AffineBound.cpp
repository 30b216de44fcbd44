#include <osgActor/detail/AffineBound.h>
#include <osgActor/core/detail/Column.h>
#include <osgActor/core/detail/HotPath.h>

#include <cmath>
#include <cstdint>
#include <cstring>

namespace osgActor {
namespace detail {

namespace {

typedef float FourFloats __attribute__((vector_size(16)));
/** The same at a float's alignment, to load a sphere where it is. */
typedef float UnalignedFourFloats __attribute__((vector_size(16), aligned(4)));

/** A point of the node's frame (x, y, z: each a lane broadcast), the matrix's rows as columns: the point moved into
  * the parent's frame in the first three lanes, each summed in Matrixd::preMult(const Vec3f&)'s order, rounded to
  * float (the last lane is the matrix's last column's sum, 1 for an affine matrix). Lane by lane, so four wide in the
  * AVX2 clone. */
OSGACTOR_INLINE FourFloats moved(Column x, Column y, Column z, const Column* rows)
{
    return __builtin_convertvector(((rows[0] * x + rows[1] * y) + rows[2] * z) + rows[3], FourFloats);
}

/** Lane k of v in every lane. */
template <int k>
OSGACTOR_INLINE Column broadcastLane(Column v)
{
    return __builtin_shufflevector(v, v, k, k, k, k);
}

/** osg::Vec3f's length() of the first three lanes of to - from, in float, in its order. */
OSGACTOR_INLINE float distance(FourFloats to, FourFloats from)
{
    const FourFloats d = to - from;
    const FourFloats squares = d * d;
    return std::sqrt(squares[0] + squares[1] + squares[2]);
}

} // namespace

// Built for x86-64-v3 too, and compiled without contracting products and sums into fused multiply-adds (this file's
// options), so both clones give OSG's bits: the translating root's bound and its actor's, at every frame.
OSGACTOR_HOT_PATH bool moveBoundByAffine(osg::BoundingSphere& sphere, const osg::Matrixd& matrix)
{
    static_assert(sizeof(osg::BoundingSphere) == sizeof(FourFloats), "a sphere is its centre and radius");
    const float radius = sphere.radius();
    if (!(radius >= 0.0f)) return true; // !sphere.valid()
    // The last column (0, 0, 0, 1), a zero of either sign (as compared in double), by the bits: one branch.
    std::uint64_t last[4];
    for (int row = 0; row < 4; ++row) std::memcpy(&last[row], matrix.ptr() + 4 * row + 3, sizeof last[row]);
    if ((((last[0] | last[1] | last[2]) << 1) != 0) | (last[3] != 0x3ff0000000000000u)) return false;
    const FourFloats lanes = *reinterpret_cast<const UnalignedFourFloats*>(&sphere); // the centre, then the radius
    // Every lane finite: a difference with itself is 0 for a finite value, NaN otherwise.
    const FourFloats zeros = lanes - lanes;
    if (zeros[0] + zeros[1] + zeros[2] + zeros[3] != 0.0f) return false;
    const double* m = matrix.ptr(); // row by row: m[4 * row + column]
    const Column rows[4] = {loadColumn(m), loadColumn(m + 4), loadColumn(m + 8), loadColumn(m + 12)};
    const Column centre = __builtin_convertvector(lanes, Column);
    // The points a radius off the centre along the axes, as osg::Transform::computeBound() makes them (in float).
    const FourFloats radii = {radius, radius, radius, radius};
    const Column dashes = __builtin_convertvector(lanes + radii, Column);
    const Column x = broadcastLane<0>(centre), y = broadcastLane<1>(centre), z = broadcastLane<2>(centre);
    const FourFloats movedCentre = moved(x, y, z, rows);
    const float lengthX = distance(moved(broadcastLane<0>(dashes), y, z, rows), movedCentre);
    const float lengthY = distance(moved(x, broadcastLane<1>(dashes), z, rows), movedCentre);
    const float lengthZ = distance(moved(x, y, broadcastLane<2>(dashes), rows), movedCentre);
    float movedRadius = lengthX;
    if (movedRadius < lengthY) movedRadius = lengthY;
    if (movedRadius < lengthZ) movedRadius = lengthZ;
    sphere.set(osg::Vec3f(movedCentre[0], movedCentre[1], movedCentre[2]), movedRadius);
    return true;
}

} // namespace detail
} // namespace osgActor
