#!/bin/sh
# same_frame_by_time_and_range.sh <osgactorrender> <scene> <folder>: the frame osgactorrender renders with
# --time 0.5 --fps 20 is byte for byte frame 10 of --frames 0 10 --fps 20 (the scene is stepped from time 0 at the
# frame rate either way), and it is not the frame at time 0 (the scene's players did advance).
render="$1"
scene="$2"
out="$3"
rm -rf "$out" && mkdir -p "$out" || exit 1
common="--size 160 120 --eye 0 -4 1 --center 0 0 0.7"
"$render" "$scene" $common --time 0.5 --fps 20 -o "$out/time.png" >/dev/null || exit 1
"$render" "$scene" $common --frames 0 10 --fps 20 -o "$out/range_%02d.png" >/dev/null || exit 1
"$render" "$scene" $common --frames 10 10 --fps 20 -o "$out/alone_%02d.png" >/dev/null || exit 1
"$render" "$scene" $common --time 0 -o "$out/start.png" >/dev/null || exit 1
cmp "$out/time.png" "$out/range_10.png" || { echo "--time 0.5 differs from frame 10 of 0..10" >&2; exit 1; }
cmp "$out/alone_10.png" "$out/range_10.png" || { echo "--frames 10 10 differs from frame 10 of 0..10" >&2; exit 1; }
if cmp -s "$out/time.png" "$out/start.png"; then
    echo "--time 0.5 shows the frame of time 0: the clip did not advance" >&2
    exit 1
fi
exit 0
