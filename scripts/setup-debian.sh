#!/usr/bin/env bash
# Installs, from Debian 12's own packages, everything osgActor needs to build, test, render and benchmark.
# Safe to run again: it installs only what is missing. Needs root (or sudo) when something is missing.
set -euo pipefail

packages=(
    build-essential cmake pkg-config git
    ccache                                 # compiles again only what changed (scripts/build.sh; the clean-clone check)
    libopenscenegraph-dev openscenegraph   # OSG 3.6 headers, libraries, osgDB plugins, osgviewer/osgconv
    libglm-dev                             # the core's math
    libtinygltf-dev                        # the glTF reader (osgActor/import)
    libassimp-dev                          # the Collada, FBX and DirectX reader (osgActor/import)
    libosmesa6-dev                         # offscreen rendering
    libegl-dev libopengl-dev               # the GPU draw benchmark's headless context (EGL, glvnd)
    fonts-dejavu-core                      # the viewer panel's font
    libgtest-dev libgmock-dev googletest   # unit tests
    libbenchmark-dev                       # benchmarks
    assimp-testmodels                      # real BVH, glTF, Collada, FBX and .x files used by the tests
    xvfb xauth                             # windowed smoke tests without a display
    libgl1-mesa-dri                        # Mesa's software GL driver under Xvfb (the ASan run preloads it)
    clang libclang-rt-14-dev               # fuzzers (libFuzzer) and sanitizer builds
    gnuplot-nox                            # the benchmark's plot
    doxygen                                # the API reference (scripts/docs.sh)
    dpkg-dev file                          # cpack -G DEB (dpkg-shlibdeps, file) and its test (dpkg-checkbuilddeps)
)

missing=()
for p in "${packages[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
    echo "setup: all ${#packages[@]} packages are installed"
    exit 0
fi

echo "setup: installing ${missing[*]}"
sudo=""
if [ "$(id -u)" -ne 0 ]; then
    command -v sudo >/dev/null || { echo "setup: need root or sudo to install ${missing[*]}" >&2; exit 1; }
    sudo="sudo"
fi
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
