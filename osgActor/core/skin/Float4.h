// Internal to the library (not installed): four floats in one SSE register, for the skinning kernels. GCC and Clang
// compile their vector extension to the target's vector instructions (SSE at the x86-64 baseline, the VEX forms in
// the x86-64-v3 clone of OSGACTOR_HOT_PATH); other compilers get the same operations on a plain array.
#ifndef OSGACTOR_CORE_SKIN_FLOAT4_H
#define OSGACTOR_CORE_SKIN_FLOAT4_H 1

#include <cstring>

#if defined(__GNUC__) || defined(__clang__)
#define OSGACTOR_SKIN_INLINE inline __attribute__((always_inline))
#else
#define OSGACTOR_SKIN_INLINE inline
#endif

namespace osgActor {
namespace skin {

#if defined(__GNUC__) || defined(__clang__)
typedef float Float4 __attribute__((vector_size(16)));
#else
struct Float4
{
    float v[4];
    float& operator[](int i) { return v[i]; }
    float operator[](int i) const { return v[i]; }
};
inline Float4 operator+(const Float4& a, const Float4& b) { return {{a[0] + b[0], a[1] + b[1], a[2] + b[2], a[3] + b[3]}}; }
inline Float4 operator*(const Float4& a, const Float4& b) { return {{a[0] * b[0], a[1] * b[1], a[2] * b[2], a[3] * b[3]}}; }
inline Float4 operator-(const Float4& a, const Float4& b) { return {{a[0] - b[0], a[1] - b[1], a[2] - b[2], a[3] - b[3]}}; }
inline Float4 operator-(const Float4& a) { return {{-a[0], -a[1], -a[2], -a[3]}}; }
inline Float4 operator*(const Float4& a, float s) { return {{a[0] * s, a[1] * s, a[2] * s, a[3] * s}}; }
inline Float4 operator*(float s, const Float4& a) { return a * s; }
inline Float4& operator+=(Float4& a, const Float4& b) { return a = a + b; }
#endif

/** Four floats from memory with no alignment required. */
OSGACTOR_SKIN_INLINE Float4 loadFloat4(const float* from)
{
    Float4 value;
    std::memcpy(&value, from, sizeof value);
    return value;
}

OSGACTOR_SKIN_INLINE Float4 makeFloat4(float x, float y, float z, float w)
{
    Float4 value;
    value[0] = x;
    value[1] = y;
    value[2] = z;
    value[3] = w;
    return value;
}

/** The vector (pick(A), pick(B), pick(C), pick(D)) where pick(i) is a[i] for i < 4 and b[i - 4] otherwise. */
template <int A, int B, int C, int D>
OSGACTOR_SKIN_INLINE Float4 shuffle(const Float4& a, const Float4& b)
{
#if defined(__clang__)
    return __builtin_shufflevector(a, b, A, B, C, D);
#elif defined(__GNUC__)
    typedef int Int4 __attribute__((vector_size(16)));
    return __builtin_shuffle(a, b, Int4{A, B, C, D});
#else
    const auto pick = [&](int i) { return i < 4 ? a[i] : b[i - 4]; };
    return makeFloat4(pick(A), pick(B), pick(C), pick(D));
#endif
}

OSGACTOR_SKIN_INLINE float dot4(const Float4& a, const Float4& b)
{
    const Float4 p = a * b;
    return (p[0] + p[1]) + (p[2] + p[3]);
}

} // namespace skin
} // namespace osgActor

#endif
