# Sourced by scripts/test-sanitizers.sh and scripts/fuzz.sh: how the two sanitizer build directories are configured
# (docs/robustness.md, "Sanitizers" and "Timings" say why these flags). Both build the library, plugins and tests,
# not the applications, examples or benchmarks (the tests cover their code, or they time things).
#
#   asan  clang, -O0 -gline-tables-only, AddressSanitizer + UBSan, and the libFuzzer targets (fuzz/): one build
#         serves the whole test suite and the fuzzers. The OSG-free core (osgActorCore: the parsers, IK, FK) is
#         compiled at -O1 with libFuzzer's coverage (-fsanitize=fuzzer-no-link), so the fuzzers run at the speed
#         they were tuned for; everything else at -O0, which compiles in less than half the time of -O1.
#   tsan  the default compiler (GCC, as the normal build), -O1 -g, ThreadSanitizer.

# sanitizer_configure <asan|tsan> <build dir>; needs $root, the repository root.
sanitizer_configure() {
    local kind="$1" build="$2" flags extra=() compiler=()
    case "$kind" in
        asan)
            # A directory configured with GCC (the layout before clang) cannot be switched in place.
            if [ -f "$build/CMakeCache.txt" ] && ! grep -q '^CMAKE_CXX_COMPILER:.*clang' "$build/CMakeCache.txt"; then
                echo "sanitizers: $build was configured with GCC; configuring it afresh with clang"
                rm -rf "$build"
            fi
            compiler=(CXX=clang++)
            flags="-fsanitize=address,undefined -fno-sanitize-recover=all"
            extra=(-DOSGACTOR_BUILD_FUZZERS=ON
                   "-DCMAKE_CXX_FLAGS=-O0 -gline-tables-only -fno-omit-frame-pointer $flags")
            ;;
        tsan)
            flags="-fsanitize=thread"
            extra=("-DCMAKE_CXX_FLAGS=-O1 -g -fno-omit-frame-pointer $flags")
            ;;
        *) echo "sanitizer_configure: no such build: $kind" >&2; return 2 ;;
    esac
    env "${compiler[@]}" cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Sanitize "${extra[@]}" \
        -DCMAKE_EXE_LINKER_FLAGS="$flags" -DCMAKE_SHARED_LINKER_FLAGS="$flags" -DCMAKE_MODULE_LINKER_FLAGS="$flags" \
        -DOSGACTOR_BUILD_APPLICATIONS=OFF -DOSGACTOR_BUILD_BENCHMARKS=OFF >/dev/null
}
