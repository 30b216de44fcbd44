#!/usr/bin/env bash
# Checks that the repository alone holds everything the demo and the tests need: copies the committed tree (git
# archive HEAD) into a temporary folder that holds nothing else, and there, with the copy's own scripts, builds,
# renders the demo offscreen (scripts/demo.sh without a display) and runs the quick suite (OSGACTOR_QUICK=1
# scripts/test.sh). Uncommitted changes are not in the copy: the script says so when there are some.
#
# Cost: a second build, without the benchmarks. When the main build went through ccache (scripts/build.sh does where
# it is installed), this one does too, and takes every object from the main build's (no compile command holds a path
# of either tree: tests/TestPaths). Otherwise the copy is built without debug information. docs/robustness.md
# ("Timings") has the figures. scripts/test.sh runs it after the quick suite; OSGACTOR_CLEAN_CLONE=0 leaves it out there.
#
# In place: where this tree is itself a clean clone (CI's checkout), a copy would repeat the very run that made it.
# scripts/test.sh says so (OSGACTOR_CLEAN_CLONE_IN_PLACE=1) when, before it built anything, the tree held nothing but
# committed files (git status, ignored files included) and its folder held nothing but the tree. Then the same checks
# run here: no committed file names this tree's path, and the demo renders offscreen; the quick suite has just passed
# by the same test command.
#
# Environment: OSGACTOR_JOBS (parallel jobs), OSGACTOR_KEEP_CLEAN_CLONE=1 (keep the copy and its build afterwards).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
jobs="${OSGACTOR_JOBS:-$(nproc)}"
start=$SECONDS

say() { echo "check-clean-clone: $*"; }
fail() {
    echo "check-clean-clone: $*" >&2
    exit 1
}

commit="$(git -C "$root" rev-parse --short HEAD)"
changes="$(git -C "$root" status --porcelain | wc -l)"
if [ "$changes" -gt 0 ]; then
    say "the working tree has $changes uncommitted changes (git status): they are NOT in this check, which copies" \
        "the commit $commit"
fi

# No committed file names this tree's own path (which would work here and nowhere else): in the copy, every file; in
# place, the files git tracks (the build folder names the path, of course).
check_no_own_path() {
    local tree="$1" named
    if [ "$tree" = "$root" ]; then
        named="$(git -C "$root" grep -IlF "$root" || true)"
    else
        named="$(cd "$tree" && grep -rIlF "$root" . | sed 's|^\./||' || true)"
    fi
    [ -z "$named" ] || fail "these files name $root:"$'\n'"$named"
}

# The demo without a display, by the tree's own command: it builds, then renders the showcase offscreen into out.
# Whatever the render says beyond its own lines ("demo: ...", "osgactorrender: ...") is a warning (a file osgDB could
# not find, say): the check fails on it.
check_demo() {
    local tree="$1" out="$2" log said frames
    log="$(mktemp)"
    (cd "$tree" && unset DISPLAY OSG_LIBRARY_PATH OSG_FILE_PATH &&
        OSGACTOR_DEMO_OUT="$out" OSGACTOR_JOBS="$jobs" scripts/demo.sh) 2>&1 | tee "$log"
    said="$(sed -n '/^demo: no display/,$p' "$log" | grep -vE '^(demo|osgactorrender): ' || true)"
    rm -f "$log"
    [ -z "$said" ] || fail "the demo's render said:"$'\n'"$said"
    frames=("$out"/frame_*.png)
    { [ ${#frames[@]} -eq 60 ] && [ -s "$out/contact_sheet.png" ]; } ||
        fail "the demo rendered ${#frames[@]} frames (60 expected) or no contact sheet"
    say "demo: 60 frames and the contact sheet in $out"
}

if [ "${OSGACTOR_CLEAN_CLONE_IN_PLACE:-0}" = 1 ]; then
    say "this tree is itself a clean clone (nothing but committed files, nothing beside it): checked in place"
    check_no_own_path "$root"
    out="$(mktemp -d)"
    trap 'rm -rf "$out"' EXIT
    check_demo "$root" "$out"
    say "the commit $commit builds, renders the demo and passes the quick suite alone, in $((SECONDS - start)) s"
    exit 0
fi

# A folder holding the copy and nothing else, named after this tree so that two trees' checks never share one.
parent="${TMPDIR:-/tmp}/osgactor-clean-clone-$(id -u)-$(printf '%s' "$root" | cksum | cut -d ' ' -f 1)"
clone="$parent/osgActor"
rm -rf "$parent"
mkdir -p "$clone"
[ "${OSGACTOR_KEEP_CLEAN_CLONE:-0}" = 1 ] || trap 'rm -rf "$parent"' EXIT
git -C "$root" archive --format=tar HEAD | tar -x -C "$clone"
[ "$(ls -A "$parent")" = osgActor ] || fail "$parent holds more than the copy"
say "commit $commit copied to $clone"
check_no_own_path "$clone"

# The build as the copy's scripts make it (the benchmarks left out: neither the demo nor the tests use them). When the
# main build went through ccache, so does this one, with the same flags: paths below $parent are made relative for
# ccache (base_dir), so the copy's compile commands match the main tree's and their objects come from the cache.
# Otherwise nothing can be reused, and the copy is compiled without debug information (the same code as the main
# build's; a test file compiles in about 30% less time).
configure=(-DCMAKE_BUILD_TYPE=RelWithDebInfo -DOSGACTOR_BUILD_BENCHMARKS=OFF)
main_cache="${OSGACTOR_BUILD_DIR:-$root/build}/CMakeCache.txt"
if command -v ccache >/dev/null && grep -qx "CMAKE_CXX_COMPILER_LAUNCHER:STRING=ccache" "$main_cache" 2>/dev/null; then
    export CCACHE_BASEDIR="$parent" CCACHE_NOHASHDIR=true
    configure+=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
    ccache_before="$(ccache --print-stats 2>/dev/null || true)"
    say "building through ccache, as the main build did"
else
    configure+=("-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O2 -DNDEBUG")
    say "building without debug information (the main build did not go through ccache: nothing to reuse)"
fi
cmake -S "$clone" -B "$clone/build" "${configure[@]}" >/dev/null
# The copy's scripts work in the copy: its build/ and out/demo/, whatever this shell points them at.
unset OSGACTOR_BUILD_DIR
check_demo "$clone" "$clone/out/demo"

# The quick suite, by the copy's own test command.
(cd "$clone" && OSGACTOR_QUICK=1 OSGACTOR_JOBS="$jobs" scripts/test.sh)

if [ -n "${ccache_before:-}" ]; then
    count() { awk -v key="$1" '$1 == key { print $2 }' <<<"$2"; }
    ccache_after="$(ccache --print-stats)"
    hits=$(($(count direct_cache_hit "$ccache_after") + $(count preprocessed_cache_hit "$ccache_after") -
        $(count direct_cache_hit "$ccache_before") - $(count preprocessed_cache_hit "$ccache_before")))
    misses=$(($(count cache_miss "$ccache_after") - $(count cache_miss "$ccache_before")))
    say "ccache: $hits compiles from the cache, $misses compiled (others' builds at the same time count too)"
fi
say "the commit $commit builds, renders the demo and passes the quick suite alone, in $((SECONDS - start)) s"
