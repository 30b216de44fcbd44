#!/usr/bin/env bash
# Checks that the repository alone holds everything the demo and the tests need: copies the committed tree (git
# archive HEAD) into a temporary folder that holds nothing else, and there, with the copy's own scripts, builds,
# renders the demo offscreen (scripts/demo.sh without a display) and runs the quick suite (OSGACTOR_QUICK=1
# scripts/test.sh). Uncommitted changes are not in the copy: the script says so when there are some.
#
# Cost: a second build, without the benchmarks. When the main build went through ccache, this one does too, and every
# object whose compile command does not hold the copy's path (the library, plugins, applications: everything but the
# tests, which are given their data folders' paths) comes from the main build's; the copy's folder depends only on
# this tree's path, so from the second run on the tests' objects come from the cache too. Otherwise the copy is built
# without debug information. docs/robustness.md ("Timings") has the figures. scripts/test.sh runs it after the quick suite;
# OSGACTOR_CLEAN_CLONE=0 leaves it out there.
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

# A folder holding the copy and nothing else, named after this tree so that two trees' checks never share one.
parent="${TMPDIR:-/tmp}/osgactor-clean-clone-$(id -u)-$(printf '%s' "$root" | cksum | cut -d ' ' -f 1)"
clone="$parent/osgActor"
rm -rf "$parent"
mkdir -p "$clone"
[ "${OSGACTOR_KEEP_CLEAN_CLONE:-0}" = 1 ] || trap 'rm -rf "$parent"' EXIT
git -C "$root" archive --format=tar HEAD | tar -x -C "$clone"
[ "$(ls -A "$parent")" = osgActor ] || fail "$parent holds more than the copy"
say "commit $commit copied to $clone"

# No committed file names this tree's own path (which would work here and nowhere else).
if grep -rIl --exclude-dir=.git -F "$root" "$clone" >"$parent.paths" 2>/dev/null; then
    sed "s|^$clone/||" "$parent.paths" >&2
    rm -f "$parent.paths"
    fail "the files above name $root"
fi
rm -f "$parent.paths"

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
unset OSGACTOR_BUILD_DIR OSGACTOR_DEMO_OUT

# The demo without a display: it builds, then renders the showcase offscreen. Whatever the render says beyond its own
# lines ("demo: ...", "osgactorrender: ...") is a warning (a file osgDB could not find, say): the check fails on it.
unset DISPLAY OSG_LIBRARY_PATH OSG_FILE_PATH
(cd "$clone" && OSGACTOR_JOBS="$jobs" scripts/demo.sh) 2>&1 | tee "$parent.demo.log"
render_said="$(sed -n '/^demo: no display/,$p' "$parent.demo.log" | grep -vE '^(demo|osgactorrender): ' || true)"
rm -f "$parent.demo.log"
[ -z "$render_said" ] || fail "the demo's render said:"$'\n'"$render_said"
frames=("$clone"/out/demo/frame_*.png)
{ [ ${#frames[@]} -eq 60 ] && [ -s "$clone/out/demo/contact_sheet.png" ]; } ||
    fail "the demo rendered ${#frames[@]} frames (60 expected) or no contact sheet"
say "demo: 60 frames and the contact sheet in the copy's out/demo"

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
