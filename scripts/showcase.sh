#!/usr/bin/env bash
# Regenerates data/showcase.osgt with osgactorshowcase (after a change to applications/showcase/ShowcaseScene.cpp or
# to what the rigs' wrappers write, ShowcaseWrappers.cpp).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${OSGACTOR_BUILD_DIR:-$root/build}"
"$build/bin/osgactorshowcase" "$root/data/showcase.osgt"
