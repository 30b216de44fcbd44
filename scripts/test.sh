#!/usr/bin/env bash
# The README's test command: installs what is missing, builds, and runs the whole test suite; then the check that the
# committed tree works alone (scripts/check-clean-clone.sh) and the robustness steps (docs/robustness.md): the long
# soak test, the ThreadSanitizer runs, the whole suite under AddressSanitizer +
# UBSan, and the bounded fuzz runs (OSGACTOR_FUZZ_SECONDS per parser; the fuzzers come from the ASan build). Each
# step says how long it took. OSGACTOR_QUICK=1 stops after the quick suite. Extra arguments go to the quick suite's
# ctest.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${OSGACTOR_BUILD_DIR:-$root/build}"
jobs="${OSGACTOR_JOBS:-$(nproc)}"

timings=()
# step <name> <command...>: runs the command and keeps its duration for the summary.
step() {
    local name="$1" start=$SECONDS
    shift
    echo "== test.sh: $name"
    "$@"
    timings+=("$name: $((SECONDS - start)) s")
}
summary() {
    echo "== test.sh: timings"
    printf '   %s\n' "${timings[@]}"
}
trap summary EXIT

# Whether this tree is itself a clean clone (CI's checkout), seen before anything is built: nothing in it but
# committed files, ignored ones included, and nothing beside it in its folder. The clean-clone check then checks it in
# place rather than copying it (scripts/check-clean-clone.sh).
clean_clone_here=0
if tree_status="$(git -C "$root" status --porcelain --ignored 2>/dev/null)" && [ -z "$tree_status" ] &&
    [ "$(ls -A "$root/..")" = "$(basename "$root")" ]; then
    clean_clone_here=1
fi

step setup "$root/scripts/setup-debian.sh"
step build "$root/scripts/build.sh"
step tests bash -c 'cd "$1" && shift && ctest --output-on-failure -j "$@"' _ "$build" "$jobs" -LE long "$@"
if [ "${OSGACTOR_QUICK:-0}" = 1 ]; then
    echo "== test.sh: OSGACTOR_QUICK=1: no soak, sanitizer or fuzz runs"
    exit 0
fi
# The repository alone: the committed tree copied where nothing is beside it, built, the demo rendered and the quick
# suite run there (scripts/check-clean-clone.sh; OSGACTOR_CLEAN_CLONE=0 leaves it out).
if [ "${OSGACTOR_CLEAN_CLONE:-1}" = 1 ]; then
    OSGACTOR_CLEAN_CLONE_IN_PLACE=$clean_clone_here step clean-clone "$root/scripts/check-clean-clone.sh"
fi
step soak bash -c 'cd "$1" && ctest --output-on-failure -L long' _ "$build"
# ThreadSanitizer, then the whole suite under AddressSanitizer + UBSan: a second build of the library and tests,
# made cheap by clang at -O0 with line tables only; it also holds the fuzzers (docs/robustness.md, timings).
step tsan "$root/scripts/test-sanitizers.sh" tsan
step asan "$root/scripts/test-sanitizers.sh" asan
# 45 s per parser, the parsers side by side on the cores (scripts/fuzz.sh), within CI's budget (docs/robustness.md,
# timings).
export OSGACTOR_FUZZ_SECONDS="${OSGACTOR_FUZZ_SECONDS:-45}"
step fuzz "$root/scripts/fuzz.sh"
