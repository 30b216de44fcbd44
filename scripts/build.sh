#!/usr/bin/env bash
# Configures and builds osgActor into build/ (or $OSGACTOR_BUILD_DIR). Extra arguments go to cmake's configure.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${OSGACTOR_BUILD_DIR:-$root/build}"
jobs="${OSGACTOR_JOBS:-$(nproc)}"
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo "$@" >/dev/null
cmake --build "$build" -j "$jobs"
