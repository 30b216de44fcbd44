// Internal to the library (not installed): 3x3 rotations as three columns of four doubles (the fourth 0), the form
// RetargetJob keeps its per-frame matrices in, so a product is three broadcasts and three multiply-adds a column in
// one vector register (see ../Column.h: 4 wide in the AVX2 clone of a hot path, two SSE2 halves in the baseline).
// Stored as 12 doubles, or read from the upper 3x3 of a glm::dmat4, whose columns are 4 doubles too.
#ifndef OSGACTOR_CORE_RETARGET_ROTATIONCOLUMNS_H
#define OSGACTOR_CORE_RETARGET_ROTATIONCOLUMNS_H 1

#include "../detail/Column.h"

#include <glm/ext/matrix_double3x3.hpp>
#include <glm/ext/matrix_double4x4.hpp>

namespace osgActor {
namespace retarget_detail {

/** A rotation's three columns (x, y, z, 0). */
struct RotationColumns
{
    Column c[3];
};

/** Doubles per stored RotationColumns. */
constexpr unsigned kRotationDoubles = 12;

OSGACTOR_INLINE RotationColumns identityColumns()
{
    return {{Column{1.0, 0.0, 0.0, 0.0}, Column{0.0, 1.0, 0.0, 0.0}, Column{0.0, 0.0, 1.0, 0.0}}};
}

OSGACTOR_INLINE RotationColumns loadRotation(const double* m)
{
    return {{loadColumn(m), loadColumn(m + 4), loadColumn(m + 8)}};
}

OSGACTOR_INLINE void storeRotation(double* m, const RotationColumns& r)
{
    for (unsigned col = 0; col < 3; ++col) storeColumn(m + 4 * col, r.c[col]);
}

/** The upper 3x3 of an affine matrix (its fourth row is 0 there). */
OSGACTOR_INLINE RotationColumns loadRotation(const glm::dmat4& m) { return loadRotation(&m[0][0]); }

/** The same as padded columns, for the rig's constants (glm's dmat3 columns are 3 doubles). */
inline void storeRotation(double* m, const glm::dmat3& r)
{
    for (unsigned col = 0; col < 3; ++col)
    {
        for (unsigned row = 0; row < 3; ++row) m[4 * col + row] = r[col][row];
        m[4 * col + 3] = 0.0;
    }
}

inline glm::dmat3 toMat3(const RotationColumns& r)
{
    glm::dmat3 m;
    for (unsigned col = 0; col < 3; ++col)
        for (unsigned row = 0; row < 3; ++row) m[col][row] = r.c[col][row];
    return m;
}

/** x a0 + y a1 + z a2: the vector (x, y, z) through the columns a. */
OSGACTOR_INLINE Column combine(const RotationColumns& a, double x, double y, double z)
{
    return a.c[0] * x + a.c[1] * y + a.c[2] * z;
}

OSGACTOR_INLINE Column combine(const RotationColumns& a, Column v) { return combine(a, v[0], v[1], v[2]); }

/** a * b. */
OSGACTOR_INLINE RotationColumns multiply(const RotationColumns& a, const RotationColumns& b)
{
    return {{combine(a, b.c[0]), combine(a, b.c[1]), combine(a, b.c[2])}};
}

/** a^T: the rows of a as columns, by whole-register shuffles (element by element, it is a chain of inserts). With
  * a_rc the element of row r and column c: */
OSGACTOR_INLINE RotationColumns transpose(const RotationColumns& a)
{
    const Column upperLeft = __builtin_shufflevector(a.c[0], a.c[1], 0, 4, 1, 5);  // a00 a01 a10 a11
    const Column lowerLeft = __builtin_shufflevector(a.c[0], a.c[1], 2, 6, 3, 7);  // a20 a21 0 0
    return {{__builtin_shufflevector(upperLeft, a.c[2], 0, 1, 4, 7),  // a00 a01 a02 0
             __builtin_shufflevector(upperLeft, a.c[2], 2, 3, 5, 7),  // a10 a11 a12 0
             __builtin_shufflevector(lowerLeft, a.c[2], 0, 1, 6, 7)}}; // a20 a21 a22 0
}

/** Four columns (x, y, z, 0), one per lane, as three columns of their x, y and z: the 4x4 transpose, less its last
  * row. Shuffle indices count the lanes of both arguments, the second's from 4. */
OSGACTOR_INLINE void transposeToLanes(const Column v[4], Column& x, Column& y, Column& z)
{
    const Column xz01 = __builtin_shufflevector(v[0], v[1], 0, 4, 2, 6); // x0 x1 z0 z1
    const Column y01 = __builtin_shufflevector(v[0], v[1], 1, 5, 3, 7);  // y0 y1 0 0
    const Column xz23 = __builtin_shufflevector(v[2], v[3], 0, 4, 2, 6); // x2 x3 z2 z3
    const Column y23 = __builtin_shufflevector(v[2], v[3], 1, 5, 3, 7);  // y2 y3 0 0
    x = __builtin_shufflevector(xz01, xz23, 0, 1, 4, 5);
    y = __builtin_shufflevector(y01, y23, 0, 1, 4, 5);
    z = __builtin_shufflevector(xz01, xz23, 2, 3, 6, 7);
}

/** m * R_axis(angle), from its cosine and sine: the columns the axis rotation mixes (X: y and z, Y: z and x, Z: x
  * and y). */
template <unsigned I, unsigned J>
OSGACTOR_INLINE void mixColumns(RotationColumns& m, double c, double s)
{
    const Column ci = m.c[I], cj = m.c[J];
    m.c[I] = ci * c + cj * s;
    m.c[J] = cj * c - ci * s;
}

OSGACTOR_INLINE void postRotate(RotationColumns& m, unsigned axis, double c, double s)
{
    switch (axis)
    {
    case 0: mixColumns<1, 2>(m, c, s); break;
    case 1: mixColumns<2, 0>(m, c, s); break;
    default: mixColumns<0, 1>(m, c, s); break;
    }
}

} // namespace retarget_detail
} // namespace osgActor

#endif
