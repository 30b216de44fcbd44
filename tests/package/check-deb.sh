#!/usr/bin/env bash
# Makes the Debian package of a build (cpack -G DEB) and has dpkg install it into a throwaway root under WORK (with
# its own empty dpkg database), leaving the system's /usr alone; check-install.sh then uses what dpkg put there. The
# package's dependencies are checked against this machine's installed packages. In the throwaway root dpkg unpacks
# the package but does not configure it: configuring runs the package's postinst (ldconfig, which CPack adds for
# libraries in /usr/lib) in a chroot of that root, which holds no shell.
#
#   check-deb.sh BUILD WORK LIBDIR SOURCE
#
# Writes WORK/cpack (the .deb) and WORK/root (the package under WORK/root/usr). With OSGACTOR_PACKAGE_SYSTEM_INSTALL=1,
# as root, it then installs the package into the system for real (dpkg -i: dependencies, postinst and all), runs
# check-install.sh on /usr (where CMake, pkg-config and osgDB look by default), and purges it again, even when a check
# fails. Not for a shared machine's test runs: for a packager, by hand.
set -euo pipefail
build="$1" work="$2" libdir="$3" source="$4"
rm -rf "$work"
mkdir -p "$work"

fail() {
    echo "check-deb.sh: $*" >&2
    exit 1
}

cpack -G DEB --config "$build/CPackConfig.cmake" -B "$work/cpack" >"$work/cpack.log" 2>&1 ||
    { cat "$work/cpack.log"; fail "cpack failed"; }
debs=("$work"/cpack/*.deb)
{ [ ${#debs[@]} -eq 1 ] && [ -f "${debs[0]}" ]; } || fail "cpack made ${#debs[@]} packages: ${debs[*]}"
deb="${debs[0]}"
dpkg-deb --info "$deb"

# Every dependency is met by what this machine has installed (the libraries dpkg-shlibdeps found, and the -dev
# packages whose headers a consumer compiles against).
depends="$(dpkg-deb --field "$deb" Depends)"
for required in "libopenscenegraph-dev " "libglm-dev" "libosmesa6-dev" "libopenscenegraph[0-9]"; do
    grep -q "$required" <<<"$depends" || fail "Depends names no $required: $depends"
done
dpkg-checkbuilddeps -d "$depends" /dev/null || fail "this machine does not have what the package depends on"

# dpkg unpacks it into the throwaway root. Its database there is empty, so the dependencies, checked above against
# the real one, are not looked for again.
root="$work/root"
mkdir -p "$root/var/lib/dpkg/info" "$root/var/lib/dpkg/updates"
touch "$root/var/lib/dpkg/status"
dpkg=(dpkg --root="$root" --log="$work/dpkg.log")
[ "$(id -u)" -eq 0 ] || dpkg+=(--force-not-root)
"${dpkg[@]}" --force-depends --unpack "$deb"
grep -qx "Status: install ok unpacked" <<<"$("${dpkg[@]}" --status osgactor)" || fail "dpkg did not unpack it"

# What dpkg installed is laid out as OSG is: headers, library, plugins, tools, package files.
listing="$("${dpkg[@]}" --listfiles osgactor)"
for path in /usr/include/osgActor/ActorNode "/usr/$libdir/libosgActor.so.0" "/usr/$libdir/libosgActor.so" \
    "/usr/$libdir/libosgActorOffscreen.so.0" "/usr/$libdir/cmake/osgActor/osgActorRenderTest.cmake" \
    "/usr/$libdir/osgPlugins-[0-9.]*/osgdb_actor.so" "/usr/$libdir/cmake/osgActor/osgActorConfig.cmake" \
    "/usr/$libdir/pkgconfig/osgActor.pc" /usr/bin/osgactorconv /usr/bin/osgactorrender /usr/bin/osgactorviewer; do
    grep -qx "$path" <<<"$listing" || fail "the package installs no $path"
done
echo "check-deb.sh: $(basename "$deb") unpacked by dpkg into $root"

if [ "${OSGACTOR_PACKAGE_SYSTEM_INSTALL:-0}" = 1 ]; then
    dpkg-query --show osgactor >/dev/null 2>&1 && fail "an osgactor package is installed already; not replacing it"
    trap 'dpkg --purge osgactor >/dev/null' EXIT
    dpkg --install "$deb"
    grep -qx "Status: install ok installed" <<<"$(dpkg --status osgactor)" || fail "dpkg did not install it"
    check="$source/tests/package/check-install.sh"
    "$check" cmake /usr "$libdir" "$work/system-cmake" "$source"
    "$check" tools /usr "$libdir" "$work/system-tools" "$source"
    echo "check-deb.sh: installed into the system by dpkg, used from /usr, purged"
fi
