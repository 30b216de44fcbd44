#!/usr/bin/env bash
# Sanitizer runs (docs/robustness.md), each in its own build directory beside build/:
#   asan  the quick test suite (ctest -LE long; the applications' tests aside) built with AddressSanitizer +
#         UndefinedBehaviorSanitizer (GCC, as the normal build); any report fails the test that made it.
#   tsan  ThreadSanitizer on the parallel actor update (WorkerPool and ActorGroup tests, a short soak run: many
#         actors playing clips on several threads) and on osgViewer's threaded models under xvfb-run.
# Usage: scripts/test-sanitizers.sh [asan|tsan]... (both by default). OSGACTOR_JOBS as for build.sh.
# OSG itself is not built with sanitizers: scripts/sanitizers/*.supp hold the few suppressions its (and Mesa's)
# own code needs, each with its reason.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
jobs="${OSGACTOR_JOBS:-$(nproc)}"
supp="$root/scripts/sanitizers"
steps=("$@")
[ ${#steps[@]} -eq 0 ] && steps=(asan tsan)

# configure <build dir> <sanitizer flags>: the library, plugins and tests at -O1 (quicker to build, still usable
# stacks); no applications, examples or benchmarks, whose code the tests cover or which time things.
configure() {
    cmake -S "$root" -B "$1" -DCMAKE_BUILD_TYPE=Sanitize -DCMAKE_CXX_FLAGS="-O1 -g -fno-omit-frame-pointer $2" \
        -DCMAKE_EXE_LINKER_FLAGS="$2" -DCMAKE_SHARED_LINKER_FLAGS="$2" -DCMAKE_MODULE_LINKER_FLAGS="$2" \
        -DOSGACTOR_BUILD_APPLICATIONS=OFF -DOSGACTOR_BUILD_BENCHMARKS=OFF >/dev/null
}

asan() {
    local build="${OSGACTOR_ASAN_BUILD_DIR:-$root/build-asan}"
    configure "$build" "-fsanitize=address,undefined -fno-sanitize-recover=undefined"
    cmake --build "$build" -j "$jobs"
    local options="detect_leaks=1:halt_on_error=1:detect_stack_use_after_return=1"
    export LSAN_OPTIONS="suppressions=$supp/lsan.supp:print_suppressions=0"
    export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
    # osgconv_* and osgviewer_* run OSG's own (uninstrumented) programs, which cannot load instrumented plugins
    # (ASan's runtime must come first); the plugin tests load the same plugins into an instrumented program.
    # fast_unwind_on_malloc=0: OSG has no frame pointers, and the slow unwinder gives the whole stacks that the
    # suppressions match; too slow for the windowed tests (Mesa allocates all the time), which run apart.
    (cd "$build" && ASAN_OPTIONS="$options:fast_unwind_on_malloc=0" \
        ctest --output-on-failure -j "$jobs" -LE 'long|viewer' -E '^(osgconv|osgviewer)_')
    (cd "$build" && ASAN_OPTIONS="$options" ctest --output-on-failure -j "$jobs" -L viewer -E '^(osgconv|osgviewer)_')
}

tsan() {
    local build="${OSGACTOR_TSAN_BUILD_DIR:-$root/build-tsan}"
    configure "$build" "-fsanitize=thread"
    cmake --build "$build" -j "$jobs" --target osgactor_node_tests osgactor_soak_test osgactor_threaded_viewer
    # Any report makes the program exit with 66 at the end (TSan's exitcode), which fails this script.
    export TSAN_OPTIONS="suppressions=$supp/tsan.supp:second_deadlock_stack=1:history_size=4"
    export OSG_NOTIFY_LEVEL=WARN
    "$build/bin/osgactor_node_tests" --gtest_filter='WorkerPool.*:ActorGroup.*'
    OSGACTOR_SOAK_FRAMES=400 "$build/bin/osgactor_soak_test"
    local model
    for model in DrawThreadPerContext CullDrawThreadPerContext; do
        xvfb-run -a -s "-screen 0 1280x1024x24" "$build/bin/osgactor_threaded_viewer" "$model" 60
    done
}

for step in "${steps[@]}"; do
    case "$step" in
        asan|tsan) start=$SECONDS; "$step"; echo "sanitizers: $step passed in $((SECONDS - start)) s" ;;
        *) echo "usage: $0 [asan|tsan]..." >&2; exit 2 ;;
    esac
done
