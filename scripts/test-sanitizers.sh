#!/usr/bin/env bash
# Sanitizer runs (docs/robustness.md), each in its own build directory beside build/, configured by
# scripts/sanitizers/configure.sh:
#   asan  the whole quick test suite (ctest -LE long; the applications' tests aside) built with AddressSanitizer +
#         UndefinedBehaviorSanitizer (clang, -O0, the core at -O1); any report fails the test that made it. The
#         same build holds the libFuzzer targets, which scripts/fuzz.sh then runs without building anything more.
#   tsan  ThreadSanitizer (GCC) on the parallel actor update (WorkerPool and ActorGroup tests, a short soak run: many
#         actors playing clips under IK on several threads) and on osgViewer's threaded models under xvfb-run, with
#         plain and with skinned actors.
# Usage: scripts/test-sanitizers.sh [asan|tsan]... (both by default). OSGACTOR_JOBS as for build.sh;
# OSGACTOR_ASAN_BUILD_DIR, OSGACTOR_TSAN_BUILD_DIR (build-asan, build-tsan).
# OSG itself is not built with sanitizers: scripts/sanitizers/*.supp hold the few suppressions its (and Mesa's)
# own code needs, each with its reason.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
jobs="${OSGACTOR_JOBS:-$(nproc)}"
supp="$root/scripts/sanitizers"
steps=("$@")
[ ${#steps[@]} -eq 0 ] && steps=(asan tsan)

source "$supp/configure.sh"

asan() {
    local build="${OSGACTOR_ASAN_BUILD_DIR:-$root/build-asan}"
    sanitizer_configure asan "$build"
    cmake --build "$build" -j "$jobs"
    local options="detect_leaks=1:halt_on_error=1:detect_stack_use_after_return=1"
    export LSAN_OPTIONS="suppressions=$supp/lsan.supp:print_suppressions=0"
    export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
    # osgconv_* and osgviewer_* run OSG's own (uninstrumented) programs, which cannot load instrumented plugins
    # (ASan's runtime lives in the instrumented programs); the plugin tests load the same plugins into one.
    # fast_unwind_on_malloc=0: OSG has no frame pointers, and the slow unwinder gives the whole stacks that the
    # suppressions match; far too slow for the windowed tests (Mesa allocates all the time), which run apart.
    (cd "$build" && ASAN_OPTIONS="$options:fast_unwind_on_malloc=0" \
        ctest --output-on-failure -j "$jobs" -LE 'long|viewer' -E '^(osgconv|osgviewer)_')
    # Mesa's software driver (swrast_dri.so) is preloaded so that closing the GL context at exit cannot unload it:
    # its globals hold the roots of its own caches, which LeakSanitizer would otherwise report as leaks from an
    # unknown module, past any suppression.
    local dri
    dri="$(find /usr/lib -name swrast_dri.so -print -quit 2>/dev/null)"
    (cd "$build" && LD_PRELOAD="$dri" ASAN_OPTIONS="$options" \
        ctest --output-on-failure -j "$jobs" -L viewer -E '^(osgconv|osgviewer)_')
}

tsan() {
    local build="${OSGACTOR_TSAN_BUILD_DIR:-$root/build-tsan}"
    sanitizer_configure tsan "$build"
    cmake --build "$build" -j "$jobs" --target osgactor_node_tests osgactor_soak_test osgactor_threaded_viewer \
        osgactor_skinned_threaded_viewer osgactor_still_crowd_viewer
    # Any report makes the program exit with 66 at the end (TSan's exitcode), which fails this script.
    export TSAN_OPTIONS="suppressions=$supp/tsan.supp:second_deadlock_stack=1:history_size=4"
    export OSG_NOTIFY_LEVEL=WARN
    "$build/bin/osgactor_node_tests" \
        --gtest_filter='WorkerPool.*:ActorGroup.*:ActorGroupBounds.*:ActorGroupCull.*:UpdatePolicy.*:CullAsOne.*:CullPlan.*:InstancedParallelCull.*:InstancedFramesInFlight.*:InstancedNearFar.*:InstancedJointEdits.*'
    OSGACTOR_SOAK_FRAMES=400 "$build/bin/osgactor_soak_test"
    local model
    for model in DrawThreadPerContext CullDrawThreadPerContext; do
        xvfb-run -a -s "-screen 0 1280x1024x24" "$build/bin/osgactor_threaded_viewer" "$model" 60
    done
    # Instanced draws: each frame's instance buffer written by one cull (its actors' part on the group's threads)
    # while the previous frame's is drawn.
    xvfb-run -a -s "-screen 0 1280x1024x24" "$build/bin/osgactor_threaded_viewer" DrawThreadPerContext 60 instanced
    # A still instanced crowd: its kept instances found in the alternating frames, written by no cull.
    xvfb-run -a -s "-screen 0 1280x1024x24" "$build/bin/osgactor_still_crowd_viewer" DrawThreadPerContext 30
    # Skinned meshes: per-frame buffers filled in cull by two cameras' cull threads while the draw reads the others;
    # their matrices and bounds computed on the ActorGroup's threads, and the actors' cull prepared there.
    for model in DrawThreadPerContext CullDrawThreadPerContext; do
        xvfb-run -a -s "-screen 0 1280x1024x24" "$build/bin/osgactor_skinned_threaded_viewer" "$model" 40
    done
    # Skinned instancing: each frame's palettes written into its instance buffer by one cull (on the group's threads)
    # while the previous frame's are drawn.
    xvfb-run -a -s "-screen 0 1280x1024x24" "$build/bin/osgactor_skinned_threaded_viewer" DrawThreadPerContext 40 \
        instanced
    # OSG's own race between that model's second camera's cull and the next update: the file says which and why.
    # (TSan reads one suppressions file: the common one and this one together.)
    cat "$supp/tsan.supp" "$supp/tsan-cull-thread-per-camera.supp" > "$build/tsan-cull-thread-per-camera.supp"
    TSAN_OPTIONS="$TSAN_OPTIONS:suppressions=$build/tsan-cull-thread-per-camera.supp" \
        xvfb-run -a -s "-screen 0 1280x1024x24" "$build/bin/osgactor_skinned_threaded_viewer" \
        CullThreadPerCameraDrawThreadPerContext 40
    # The same instanced: one camera's cull takes the group's threads, the other culls serially or ordinarily.
    TSAN_OPTIONS="$TSAN_OPTIONS:suppressions=$build/tsan-cull-thread-per-camera.supp" \
        xvfb-run -a -s "-screen 0 1280x1024x24" "$build/bin/osgactor_skinned_threaded_viewer" \
        CullThreadPerCameraDrawThreadPerContext 40 instanced
}

for step in "${steps[@]}"; do
    case "$step" in
        asan|tsan) start=$SECONDS; "$step"; echo "sanitizers: $step passed in $((SECONDS - start)) s" ;;
        *) echo "usage: $0 [asan|tsan]..." >&2; exit 2 ;;
    esac
done
