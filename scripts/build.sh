#!/usr/bin/env bash
# Configures and builds osgActor into build/ (or $OSGACTOR_BUILD_DIR). Extra arguments go to cmake's configure.
#
# Compiles through ccache where it is installed (scripts/setup-debian.sh installs it) and no compiler launcher was
# chosen (CMAKE_CXX_COMPILER_LAUNCHER in the environment or the build's cache; OSGACTOR_CCACHE=0 leaves ccache out of
# a new build folder), with the tree's paths made relative for ccache (base_dir) and the build folder left out of its
# hash: a second tree of the same commit (scripts/check-clean-clone.sh's copy) then takes its objects from this
# build's, the tests' included (their paths are compiled apart, tests/TestPaths).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${OSGACTOR_BUILD_DIR:-$root/build}"
jobs="${OSGACTOR_JOBS:-$(nproc)}"
configure=(-DCMAKE_BUILD_TYPE=RelWithDebInfo)
launcher_chosen() {
    [ -n "${CMAKE_CXX_COMPILER_LAUNCHER:-}" ] || grep -q "^CMAKE_CXX_COMPILER_LAUNCHER:" "$build/CMakeCache.txt" 2>/dev/null
}
if [ "${OSGACTOR_CCACHE:-1}" = 1 ] && command -v ccache >/dev/null && ! launcher_chosen; then
    configure+=(-DCMAKE_CXX_COMPILER_LAUNCHER:STRING=ccache -DCMAKE_C_COMPILER_LAUNCHER:STRING=ccache)
fi
cmake -S "$root" -B "$build" "${configure[@]}" "$@" >/dev/null
if grep -qx "CMAKE_CXX_COMPILER_LAUNCHER:STRING=ccache" "$build/CMakeCache.txt"; then
    export CCACHE_BASEDIR="${CCACHE_BASEDIR:-$root}" CCACHE_NOHASHDIR="${CCACHE_NOHASHDIR:-true}"
fi
cmake --build "$build" -j "$jobs"
