#!/usr/bin/env bash
# Uses an installed osgActor as its users would, from a prefix holding nothing but the install (tests/package/
# CMakeLists.txt registers each mode as a ctest; the Debian package's check runs them on what dpkg installed).
#
#   check-install.sh cmake     PREFIX LIBDIR WORK SOURCE [CXX]  a CMake project doing only what README.md says
#                                                                (find_package + target_link_libraries), built with
#                                                                CXX (default: CMake's choice) and run; one of its
#                                                                programs loads an .actor file through osgDB
#   check-install.sh pkgconfig PREFIX LIBDIR WORK SOURCE        the README's example built with pkg-config's flags and
#                                                                run; every installed header compiles on its own
#   check-install.sh tools     PREFIX LIBDIR WORK SOURCE        the installed tools run, and OSG's osgconv converts
#                                                                through the installed plugins
#
# PREFIX is the install prefix, LIBDIR its library folder (relative, CMAKE_INSTALL_LIBDIR), WORK a folder this
# script may empty, SOURCE the osgActor source tree (the consumer's files and data/). Nothing from the build tree or
# the caller's environment is used (but CMAKE_CXX_COMPILER_LAUNCHER, a compiler cache the consumers compile through):
# the library must come from PREFIX, the plugins from PREFIX/LIBDIR.
set -euo pipefail
mode="$1" prefix="$2" libdir="$3" work="$4" source="$5" cxx="${6:-}"
lib="$prefix/$libdir"
unset LD_LIBRARY_PATH OSG_LIBRARY_PATH OSG_FILE_PATH CMAKE_PREFIX_PATH PKG_CONFIG_PATH
export OSG_NOTIFY_LEVEL=WARN
rm -rf "$work"
mkdir -p "$work"

fail() {
    echo "check-install.sh $mode: $*" >&2
    exit 1
}

# The README's example (examples/osgactorhello) prints where its joints are. By hand: the shoulder at (0, 0, 1.4);
# the shoulder's rx of -90 degrees turns the elbow's offset (0, 0, -0.3) into (0, -0.3, 0); the elbow's rx of +90
# undoes that turn for the wrist's offset (0, 0, -0.25).
expect_hello_output() {
    local output="$1"
    for line in "r_shoulder 0.000 0.000 1.400" "r_elbow 0.000 -0.300 1.400" "r_wrist 0.000 -0.300 1.150"; do
        grep -qx "$line" <<<"$(tr -s ' ' <<<"$output")" || fail "osgactorhello printed no line '$line':"$'\n'"$output"
    done
}

# The program's libosgActor is the installed one.
expect_library_from_prefix() {
    local program="$1" resolved
    resolved="$(ldd "$program" | awk '$1 ~ /^libosgActor\.so/ { print $3 }')"
    [ "$(realpath "$resolved")" = "$(realpath "$lib/libosgActor.so.0")" ] ||
        fail "$program uses '$resolved', not the library in $lib"
}

case "$mode" in
cmake)
    cp "$source/tests/package/consumer/CMakeLists.txt" "$source/tests/package/consumer/load_actor.cpp" \
        "$source/examples/osgactorhello/osgactorhello.cpp" "$work/"
    cmake -S "$work" -B "$work/build" -DCMAKE_PREFIX_PATH="$prefix" ${cxx:+-DCMAKE_CXX_COMPILER="$cxx"} >/dev/null
    cmake --build "$work/build"
    expect_library_from_prefix "$work/build/osgactorhello"
    expect_hello_output "$("$work/build/osgactorhello")"
    # osgDB finds the installed plugins as it finds OSG's own: OSG_LIBRARY_PATH names the library folder, and osgDB
    # looks in its osgPlugins-<version> folder.
    output="$(OSG_LIBRARY_PATH="$lib" "$work/build/load_actor" "$source/data/humanoid.actor" "$work/back.actor")"
    echo "$output"
    grep -q "^plugin $lib/osgPlugins-[0-9.]*/osgdb_actor.so$" <<<"$output" ||
        fail "osgDB did not take the installed plugin"
    grep -q "^actor humanoid: 18 joints, 41 DOFs, read, written and read back$" <<<"$output" ||
        fail "the humanoid did not load as it should"
    ;;
pkgconfig)
    export PKG_CONFIG_PATH="$lib/pkgconfig"
    [ "$(pkg-config --modversion osgActor)" = "$(sed -n 's/^project(osgActor VERSION \([0-9.]*\).*/\1/p' \
        "$source/CMakeLists.txt")" ] || fail "pkg-config gives another version"
    [ -f "$(pkg-config --variable=plugindir osgActor)/osgdb_actor.so" ] || fail "plugindir holds no osgdb_actor.so"
    # shellcheck disable=SC2206 # no launcher gives no word
    compile=(${CMAKE_CXX_COMPILER_LAUNCHER:-} c++ -std=c++17)
    # shellcheck disable=SC2046 # pkg-config's flags are meant to be split
    "${compile[@]}" -o "$work/osgactorhello" "$source/examples/osgactorhello/osgactorhello.cpp" \
        $(pkg-config --cflags --libs osgActor)
    expect_hello_output "$(LD_LIBRARY_PATH="$lib" "$work/osgactorhello")"
    # Every installed header, included alone in its own translation unit would be surest; one unit including all of
    # them after nothing else still finds a header that includes one that was not installed.
    (cd "$prefix/include" && find osgActor -type f | sort | sed 's/.*/#include <&>/') >"$work/all_headers.cpp"
    [ "$(wc -l <"$work/all_headers.cpp")" -gt 40 ] || fail "too few installed headers"
    # shellcheck disable=SC2046
    "${compile[@]}" -fsyntax-only -Wall -Wextra -Werror "$work/all_headers.cpp" $(pkg-config --cflags osgActor)
    ;;
tools)
    # Run paths: the tools start with no LD_LIBRARY_PATH. CMU 12_03 frame 0's root is at -1.4385 16.4063 -26.0539.
    "$prefix/bin/osgactorconv" --dump-positions --frames 0:1 "$source/data/mocap/bvh/12_03.bvh" >"$work/dump.csv"
    [ "$(sed -n 2p "$work/dump.csv")" = "0,Hips,-1.4385,16.4063,-26.0539" ] || fail "osgactorconv's dump is wrong"
    # osgDB looks for plugins under the prefixes it knows (/usr, /usr/local) and OSG_LIBRARY_PATH's folders.
    OSG_LIBRARY_PATH="$lib" "$prefix/bin/osgactorrender" "$source/data/robot_arm.actor" --size 64 48 \
        -o "$work/arm.png" >/dev/null
    [ -s "$work/arm.png" ] || fail "osgactorrender wrote no image"
    "$prefix/bin/osgactorviewer" --help >/dev/null
    # OSG's own converter, through the installed .actor and serializer plugins, and back.
    if command -v osgconv >/dev/null; then
        OSG_LIBRARY_PATH="$lib" OSG_NOTIFY_LEVEL=DEBUG osgconv "$source/data/robot_arm.actor" "$work/arm.osgt" \
            >"$work/osgconv.log" 2>&1 || { tail "$work/osgconv.log"; fail "osgconv could not convert to .osgt"; }
        for plugin in osgdb_actor osgdb_serializers_osgactor; do
            grep -q "^FindFileInPath() : USING $lib/osgPlugins-[0-9.]*/$plugin.so$" "$work/osgconv.log" ||
                fail "osgconv did not load the installed $plugin"
        done
        OSG_LIBRARY_PATH="$lib" osgconv "$work/arm.osgt" "$work/arm.actor" >/dev/null
        grep -q "^actor robot_arm {" "$work/arm.actor" || fail "the .osgt did not come back as an .actor file"
    fi
    ;;
*)
    fail "unknown mode (cmake, pkgconfig or tools)"
    ;;
esac
echo "check-install.sh $mode: the install in $prefix works"
