#!/usr/bin/env bash
# The README's demo command: installs what is missing, builds, and shows the showcase scene (data/showcase.osgt):
# - with a display ($DISPLAY set), in osgactorviewer (press h for the keys), its home view framing the actors;
# - without one, rendered offscreen (OSMesa) to PNG frames and a contact sheet, in out/demo/ (or $OSGACTOR_DEMO_OUT).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${OSGACTOR_BUILD_DIR:-$root/build}"
"$root/scripts/setup-debian.sh"
"$root/scripts/build.sh"

# osgDB finds the osgActor plugins (build/lib/osgPlugins-<ver>/) and the showcase's rigs (build/lib) here.
export OSG_LIBRARY_PATH="$build/lib${OSG_LIBRARY_PATH:+:$OSG_LIBRARY_PATH}"
scene="$root/data/showcase.osgt"

if [ -n "${DISPLAY:-}" ]; then
    echo "demo: opening osgactorviewer on $scene (press h for the keys, Esc to quit)"
    exec "$build/bin/osgactorviewer" "$scene"
fi

out="${OSGACTOR_DEMO_OUT:-$root/out/demo}"
mkdir -p "$out"
echo "demo: no display, rendering $scene offscreen"
# The camera frames the actors and the paths they walk, as osgactorviewer's home does.
"$build/bin/osgactorrender" "$scene" --size 640 360 --frames 0 59 --fps 10 \
    --frame-actors --background 0.62 0.72 0.85 \
    -o "$out/frame_%04d.png" --contact-sheet "$out/contact_sheet.png" --sheet-columns 6 --sheet-tile-width 200
echo "demo: 60 frames (6 s at 10 frames/s) in $out/frame_0000.png .. $out/frame_0059.png"
echo "demo: contact sheet $out/contact_sheet.png"
