// Internal to the library (not installed, NOT API): affine 4x4 matrices as four Columns, and their product, shared by
// the local-matrices and local-to-model jobs. Matrices are glm::dmat4 in memory (column-major, 16 doubles) whose
// bottom row is (0 0 0 1), so a product is a 3x3 rotation product plus a translation, not a full 4x4 product.
#ifndef OSGACTOR_CORE_DETAIL_AFFINECOLUMNS_H
#define OSGACTOR_CORE_DETAIL_AFFINECOLUMNS_H 1

#include "Column.h"

namespace osgActor {

/** x a0 + y a1 + z a2: a point or direction (x, y, z) taken through the three axis columns of a matrix. Every product
  * of matrices here is columns of this. */
OSGACTOR_INLINE Column combineColumns(Column a0, Column a1, Column a2, double x, double y, double z)
{
    return a0 * x + a1 * y + a2 * z;
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

} // namespace osgActor

#endif
