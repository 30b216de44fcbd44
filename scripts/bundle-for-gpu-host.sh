#!/bin/sh
# Packs what scripts/gpu-measure.sh runs into one folder, for a GPU host that has the NVIDIA driver and libglvnd
# (libEGL, libOpenGL) but not this project's packages (OSG, Assimp, tinygltf, Google Benchmark...):
#   BUNDLE/bin   the three measuring programs, stripped
#   BUNDLE/lib   libosgActor and every shared library they load but the C library, the loader and OpenGL's (the
#                host's driver provides those), with the osgDB plugins they read through (osgPlugins-<version>)
# Copy BUNDLE and the repository's data/ to the host and run scripts/gpu-measure.sh BUNDLE/bin there; it finds
# BUNDLE/lib by itself.
# Usage: scripts/bundle-for-gpu-host.sh [BUILD_DIR [BUNDLE]]   (defaults: build, gpu-bundle)
set -eu
build=$(cd "${1:-build}" && pwd)
bundle=${2:-gpu-bundle}
programs="osgactor_gpu_draw_bench osgactorbench osgactor_skin_bench"
rm -rf "$bundle"
mkdir -p "$bundle/bin" "$bundle/lib"
for program in $programs; do strip -o "$bundle/bin/$program" "$build/bin/$program"; done

# Copies into the bundle the libraries the given files load, as the loader resolves them here, but the C library,
# the loader and OpenGL's; libosgActor (from the build) stripped.
copy_libraries() {
    for file in "$@"; do ldd "$file"; done | awk '$2 == "=>" && $3 ~ /^\// { print $3 }' | sort -u |
        grep -v -E '/(libc|libm|libdl|libpthread|librt|ld-linux[^/]*|libGL|libGLX|libGLdispatch|libEGL|libOpenGL)\.so' |
        while read -r library; do
            name=$(basename "$library")
            [ -e "$bundle/lib/$name" ] && continue
            case "$name" in
            libosgActor*) strip -o "$bundle/lib/$name" "$library" ;;
            *) cp -L "$library" "$bundle/lib/$name" ;;
            esac
        done
}
for program in $programs; do copy_libraries "$build/bin/$program"; done

# osgDB's plugins: the project's, and the image formats the bench writes and the Cesium Man's textures need.
osg_plugins=$(dirname "$(ldd "$build/bin/osgactorbench" | awk '/libosgDB\.so/ { print $3 }')")
version=$(basename "$(ls -d "$osg_plugins"/osgPlugins-* | head -n 1)")
mkdir -p "$bundle/lib/$version"
for plugin in "$build/lib/$version"/*.so; do strip -o "$bundle/lib/$version/$(basename "$plugin")" "$plugin"; done
for format in png jpeg; do cp "$osg_plugins/$version/osgdb_$format.so" "$bundle/lib/$version/"; done
copy_libraries "$bundle/lib/$version"/*.so
du -sh "$bundle"
