// Internal to the library (not installed): eight floats as one value, for SkinBoundsJob's groups of eight pieces.
// GCC and Clang compile their vector extension to one AVX register in the x86-64-v3 clone of OSGACTOR_HOT_PATH and
// to two SSE registers at the x86-64 baseline; other compilers get the same operations on a plain array.
#ifndef OSGACTOR_CORE_SKIN_FLOAT8_H
#define OSGACTOR_CORE_SKIN_FLOAT8_H 1

#include "Float4.h"

#include <cmath>
#include <cstring>

namespace osgActor {
namespace skin {

#if defined(__GNUC__) || defined(__clang__)
// Every function taking or returning a Float8 is inlined (OSGACTOR_SKIN_INLINE), so the compilers' note that a
// 32-byte vector passed by value has another ABI without AVX concerns no call: off for the file that includes this.
#pragma GCC diagnostic ignored "-Wpsabi"
#endif

// GCC from 12 and Clang shuffle and join vectors with __builtin_shufflevector; elsewhere, lane by lane.
#if defined(__has_builtin)
#if __has_builtin(__builtin_shufflevector)
#define OSGACTOR_SKIN_SHUFFLEVECTOR 1
#endif
#endif
#ifndef OSGACTOR_SKIN_SHUFFLEVECTOR
#define OSGACTOR_SKIN_SHUFFLEVECTOR 0
#endif

#if defined(__GNUC__) || defined(__clang__)
typedef float Float8 __attribute__((vector_size(32)));

/** Per lane, a < b ? x : y. */
OSGACTOR_SKIN_INLINE Float8 selectLess(const Float8& a, const Float8& b, const Float8& x, const Float8& y)
{
    return a < b ? x : y;
}

/** Per lane, |a|: the sign bit cleared. */
OSGACTOR_SKIN_INLINE Float8 abs8(const Float8& a)
{
    typedef int Int8 __attribute__((vector_size(32)));
    return reinterpret_cast<Float8>(reinterpret_cast<Int8>(a) & 0x7fffffff);
}
#else
struct Float8
{
    float v[8];
    float& operator[](int i) { return v[i]; }
    float operator[](int i) const { return v[i]; }
};
template <class Op>
inline Float8 lanewise(const Float8& a, const Float8& b, Op op)
{
    Float8 r;
    for (int i = 0; i < 8; ++i) r[i] = op(a[i], b[i]);
    return r;
}
inline Float8 operator+(const Float8& a, const Float8& b) { return lanewise(a, b, [](float x, float y) { return x + y; }); }
inline Float8 operator-(const Float8& a, const Float8& b) { return lanewise(a, b, [](float x, float y) { return x - y; }); }
inline Float8 operator*(const Float8& a, const Float8& b) { return lanewise(a, b, [](float x, float y) { return x * y; }); }
inline Float8 operator-(const Float8& a) { return lanewise(a, a, [](float x, float) { return -x; }); }
inline Float8 selectLess(const Float8& a, const Float8& b, const Float8& x, const Float8& y)
{
    Float8 r;
    for (int i = 0; i < 8; ++i) r[i] = a[i] < b[i] ? x[i] : y[i];
    return r;
}
inline Float8 abs8(const Float8& a) { return lanewise(a, a, [](float x, float) { return std::abs(x); }); }
#endif

/** Eight floats from memory with no alignment required. */
OSGACTOR_SKIN_INLINE Float8 loadFloat8(const float* from)
{
    Float8 value;
    std::memcpy(&value, from, sizeof value);
    return value;
}

OSGACTOR_SKIN_INLINE void storeFloat8(float* to, const Float8& value) { std::memcpy(to, &value, sizeof value); }

/** s in every lane. */
OSGACTOR_SKIN_INLINE Float8 splatFloat8(float s)
{
    Float8 value;
    for (int i = 0; i < 8; ++i) value[i] = s;
    return value;
}

/** The vector (pick(I0), ..., pick(I7)) where pick(i) is a[i] for i < 8 and b[i - 8] otherwise. */
template <int I0, int I1, int I2, int I3, int I4, int I5, int I6, int I7>
OSGACTOR_SKIN_INLINE Float8 shuffle8(const Float8& a, const Float8& b)
{
#if OSGACTOR_SKIN_SHUFFLEVECTOR
    return __builtin_shufflevector(a, b, I0, I1, I2, I3, I4, I5, I6, I7);
#else
    const int picks[8] = {I0, I1, I2, I3, I4, I5, I6, I7};
    Float8 value;
    for (int i = 0; i < 8; ++i) value[i] = picks[i] < 8 ? a[picks[i]] : b[picks[i] - 8];
    return value;
#endif
}

/** low's four floats, then high's. */
OSGACTOR_SKIN_INLINE Float8 joinFloat4(const Float4& low, const Float4& high)
{
#if OSGACTOR_SKIN_SHUFFLEVECTOR
    return __builtin_shufflevector(low, high, 0, 1, 2, 3, 4, 5, 6, 7);
#else
    Float8 value;
    for (int i = 0; i < 4; ++i) value[i] = low[i], value[4 + i] = high[i];
    return value;
#endif
}

OSGACTOR_SKIN_INLINE Float8 min8(const Float8& a, const Float8& b) { return selectLess(b, a, b, a); }
OSGACTOR_SKIN_INLINE Float8 max8(const Float8& a, const Float8& b) { return selectLess(a, b, b, a); }

} // namespace skin
} // namespace osgActor

#endif
