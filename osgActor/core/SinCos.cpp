// Sine and cosine of a batch of angles, computed together: one range reduction serves both, and the loop has no
// branch, so GCC vectorizes it (4 angles at a time with AVX2+FMA, chosen at run time; 2 with SSE2). Built with
// -fno-trapping-math, which lets the selects vectorize, but never -ffast-math: the reduction below depends on the
// order of its operations.
#include <osgActor/core/SinCos>

#include <cmath>
#include <cstdint>

namespace osgActor {

namespace {

// pi/2 split into three parts: the first two have 30 significant bits, so j * part is exact for |j| < 2^23 and the
// reduction x - j pi/2 loses nothing (Cody and Waite). kLargestFastAngle keeps j far inside that range; larger
// angles take the library's functions.
constexpr double kTwoOverPi = 0x1.45f306dc9c883p-1;
constexpr double kHalfPi1 = 0x1.921fb54800000p+0;
constexpr double kHalfPi2 = -0x1.de973dc800000p-31;
constexpr double kHalfPi3 = -0x1.9d9cceba3f91fp-62;
constexpr double kLargestFastAngle = 1.0e6;

// Taylor coefficients: on the reduced range |r| <= pi/4 the first omitted terms (r^17 / 17!, r^18 / 18!) are below
// 1e-16, a fraction of an ulp of the results.
constexpr double kSin[] = {-1.0 / 6, 1.0 / 120, -1.0 / 5040, 1.0 / 362880, -1.0 / 39916800, 1.0 / 6227020800,
                           -1.0 / 1307674368000};
constexpr double kCos[] = {-1.0 / 2,        1.0 / 24,          -1.0 / 720,            1.0 / 40320,
                           -1.0 / 3628800,  1.0 / 479001600,   -1.0 / 87178291200,    1.0 / 20922789888000};

#define OSGACTOR_INLINE inline __attribute__((always_inline))

/** sin and cos of one angle with |x| <= kLargestFastAngle, branch-free so that the loop around it vectorizes. */
OSGACTOR_INLINE void reducedSinCos(double x, double& sine, double& cosine)
{
    const double j = std::floor(x * kTwoOverPi + 0.5); // the nearest multiple of pi/2
    const double r = ((x - j * kHalfPi1) - j * kHalfPi2) - j * kHalfPi3;
    const double r2 = r * r;
    double ps = kSin[6];
    for (int k = 5; k >= 0; --k) ps = ps * r2 + kSin[k];
    double pc = kCos[7];
    for (int k = 6; k >= 0; --k) pc = pc * r2 + kCos[k];
    const double s = r + r * r2 * ps; // sin r
    const double c = 1.0 + r2 * pc;   // cos r
    // x = r + q pi/2 with q = j mod 4: (sin, cos) of x is (s, c), (c, -s), (-s, -c), (-c, s).
    const double q = j - 4.0 * std::floor(j * 0.25);
    const bool odd = q == 1.0 || q == 3.0;
    const double sinMagnitude = odd ? c : s;
    const double cosMagnitude = odd ? s : c;
    sine = q >= 2.0 ? -sinMagnitude : sinMagnitude;
    cosine = q == 1.0 || q == 2.0 ? -cosMagnitude : cosMagnitude;
}

// The loops as a macro, pasted into each variant: a function inlined into a target("avx2") function is still
// vectorized for its own (baseline) target.
#define OSGACTOR_SINCOS_LOOPS                                                                                       \
    /* As wide as the angles, so it vectorizes with them (a sum of doubles would be added lane by lane). */          \
    std::uint64_t anyLarge = 0;                                                                                     \
    for (unsigned i = 0; i < count; ++i)                                                                            \
    {                                                                                                               \
        reducedSinCos(angles[i], sines[i], cosines[i]);                                                             \
        anyLarge |= std::fabs(angles[i]) > kLargestFastAngle ? 1u : 0u;                                             \
    }                                                                                                               \
    for (unsigned i = 0; anyLarge != 0 && i < count; ++i)                                                           \
        if (std::fabs(angles[i]) > kLargestFastAngle)                                                               \
        {                                                                                                           \
            sines[i] = std::sin(angles[i]);                                                                         \
            cosines[i] = std::cos(angles[i]);                                                                       \
        }

#if defined(__x86_64__) && defined(__GNUC__)
__attribute__((target("avx2,fma"))) void sinCosAvx2(const double* __restrict angles, double* __restrict sines,
                                                     double* __restrict cosines, unsigned count)
{
    OSGACTOR_SINCOS_LOOPS
}

bool hasAvx2()
{
    static const bool supported = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
    return supported;
}
#endif

void sinCosBaseline(const double* __restrict angles, double* __restrict sines, double* __restrict cosines,
                    unsigned count)
{
    OSGACTOR_SINCOS_LOOPS
}

} // namespace

void sinCos(const double* angles, double* sines, double* cosines, unsigned count)
{
#if defined(__x86_64__) && defined(__GNUC__)
    if (hasAvx2())
    {
        sinCosAvx2(angles, sines, cosines, count);
        return;
    }
#endif
    sinCosBaseline(angles, sines, cosines, count);
}

} // namespace osgActor
