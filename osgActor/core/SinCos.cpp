// Compiled with -O3 -ffast-math (see osgActor/CMakeLists.txt): with __FAST_MATH__ glibc's <math.h> declares the
// SIMD variants of sin and cos, and GCC vectorizes the loops below into calls to them. Only this file is built so;
// nothing else in the library depends on fast-math semantics.
#include <osgActor/core/SinCos>

#include <math.h>

namespace osgActor {

namespace {

// Two loops rather than one: GCC would fuse sin and cos of one angle into a scalar sincos, which has no vector
// variant it can call.
#define OSGACTOR_SINCOS_LOOPS                                                                                       \
    for (unsigned i = 0; i < count; ++i) sines[i] = ::sin(angles[i]);                                               \
    for (unsigned i = 0; i < count; ++i) cosines[i] = ::cos(angles[i]);

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
