#!/usr/bin/env bash
# Builds osgActor's API reference with Doxygen (docs/Doxyfile) from the public headers as `cmake --install` puts
# them, into <build>/docs/api (html/index.html). Fails, listing them, on any Doxygen warning. Exits 77 (a skip, for
# ctest) when doxygen is not installed; scripts/setup-debian.sh installs it.
# Usage: scripts/docs.sh [build folder, default build/ or $OSGACTOR_BUILD_DIR]; the build must have been built.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="$(cd "${1:-${OSGACTOR_BUILD_DIR:-$root/build}}" && pwd)"

if ! command -v doxygen >/dev/null; then
    echo "docs: doxygen is not installed (scripts/setup-debian.sh installs it)" >&2
    exit 77
fi

docs="$build/docs"
stage="$docs/stage"
rm -rf "$stage" "$docs/api"
mkdir -p "$docs"
trap 'rm -rf "$stage"' EXIT # the installed copy (libraries too) is only read here
# The public headers are the installed ones: what the install rules put under include/osgActor, nothing else.
cmake --install "$build" --prefix "$stage" >/dev/null
include="$(find "$stage" -maxdepth 2 -type d -name include | head -n 1)"
[ -d "$include/osgActor" ] || { echo "docs: the install put no headers in $stage" >&2; exit 1; }

export OSGACTOR_DOCS_INPUT="$include/osgActor"
export OSGACTOR_DOCS_STRIP="$include"
export OSGACTOR_DOCS_OUTPUT="$docs/api"
export OSGACTOR_DOCS_WARNINGS="$docs/warnings.txt"
export OSGACTOR_VERSION="$(sed -n 's/^set(PACKAGE_VERSION "\(.*\)")$/\1/p' \
    "$(find "$stage" -name osgActorConfigVersion.cmake | head -n 1)")"
mkdir -p "$OSGACTOR_DOCS_OUTPUT"
doxygen "$root/docs/Doxyfile"

if [ -s "$OSGACTOR_DOCS_WARNINGS" ]; then
    echo "docs: Doxygen warned about the public headers:" >&2
    # Named by their source files: include/osgActor/... is installed from osgActor/... of the source tree.
    sed "s|$include/|$root/|" "$OSGACTOR_DOCS_WARNINGS" >&2
    exit 1
fi
echo "docs: $OSGACTOR_DOCS_OUTPUT/html/index.html"
