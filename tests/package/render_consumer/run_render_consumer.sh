#!/bin/sh
# run_render_consumer.sh <osgActor build folder> <work folder> <data folder>: installs the built osgActor into a
# new prefix under the work folder, then configures, builds and tests tests/package/render_consumer against that
# prefix alone (no OSG_LIBRARY_PATH or LD_LIBRARY_PATH from the build tree).
set -eu
build="$1"
work="$2"
data="$3"
source="$(cd "$(dirname "$0")" && pwd)"
rm -rf "$work"
unset OSG_LIBRARY_PATH LD_LIBRARY_PATH
cmake --install "$build" --prefix "$work/prefix" >/dev/null
cmake -S "$source" -B "$work/build" -DCMAKE_PREFIX_PATH="$work/prefix" -DRENDER_CONSUMER_DATA="$data" >/dev/null
cmake --build "$work/build" -j 2 >/dev/null
cd "$work/build"
ctest --output-on-failure
