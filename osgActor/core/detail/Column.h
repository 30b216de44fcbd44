// Internal to the library (not installed): a matrix column of four doubles as one value, for the per-frame math
// (forward kinematics, sines and cosines). GCC's vector extension, so the same code is 4 wide in the AVX2 clone of
// a hot path (see HotPath.h) and two SSE2 halves in the baseline one.
#ifndef OSGACTOR_CORE_DETAIL_COLUMN_H
#define OSGACTOR_CORE_DETAIL_COLUMN_H 1

#define OSGACTOR_INLINE inline __attribute__((always_inline))
// The same for a lambda, which takes the attribute without the keyword.
#define OSGACTOR_INLINE_LAMBDA __attribute__((always_inline))

// Columns pass by value between always-inline functions only, so the warning that a 32-byte vector argument changes
// the ABI without AVX (the baseline clone) concerns no real call.
#pragma GCC diagnostic ignored "-Wpsabi"

namespace osgActor {

typedef double Column __attribute__((vector_size(32)));
/** The same at double alignment, for loads and stores of matrices wherever they are (a node's matrix). */
typedef double UnalignedColumn __attribute__((vector_size(32), aligned(8)));
/** A column's bits, for sign and select tricks; also the type of a comparison of two columns. */
typedef unsigned long long ColumnBits __attribute__((vector_size(32)));
/** The same, signed: a lane is negative where its sign bit is set. */
typedef long long ColumnSignedBits __attribute__((vector_size(32)));

OSGACTOR_INLINE Column loadColumn(const double* p) { return *reinterpret_cast<const UnalignedColumn*>(p); }
OSGACTOR_INLINE void storeColumn(double* p, Column c) { *reinterpret_cast<UnalignedColumn*>(p) = c; }

/** |c|, lane by lane: the sign bits cleared. */
OSGACTOR_INLINE Column absColumn(Column c)
{
    return reinterpret_cast<Column>(reinterpret_cast<ColumnBits>(c) & ~(ColumnBits{} + (1ull << 63)));
}

} // namespace osgActor

#endif
