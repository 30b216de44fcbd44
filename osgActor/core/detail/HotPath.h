// Internal to the library (not installed): marks a per-frame loop to be built twice, for x86-64-v3 (AVX2, FMA) and
// for the x86-64 baseline, the right one chosen once when the library is loaded (GCC's target_clones, an IFUNC). One
// clone for the whole level: "avx2,fma" would make two clones, an AVX2 one without FMA and an FMA one.
#ifndef OSGACTOR_CORE_DETAIL_HOTPATH_H
#define OSGACTOR_CORE_DETAIL_HOTPATH_H 1

// Not in sanitizer builds: the clones' IFUNC resolver runs while the library is relocated, before the sanitizer's
// runtime is set up, and the instrumented resolver crashes there (ThreadSanitizer: SIGSEGV in _dl_relocate_object).
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && !defined(__SANITIZE_THREAD__) &&             \
    !defined(__SANITIZE_ADDRESS__)
#define OSGACTOR_HOT_PATH __attribute__((target_clones("arch=x86-64-v3", "default")))
#else
#define OSGACTOR_HOT_PATH
#endif

#endif
