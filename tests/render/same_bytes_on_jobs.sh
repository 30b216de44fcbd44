#!/bin/sh
# same_bytes_on_jobs.sh <osgactorrender> <folder> <scene> <options...>: the scene's frames are the same bytes
# rendered in one process, in one process with llvmpipe on 3 threads, in 2 processes and in 3 (--jobs), and so are
# their contact sheets (assembled from the frames written, or from frames the processes hand over with
# --no-frames); and the scene moves (its first and last frames differ), so that the comparison can fail.
render="$1"
out="$2"
shift 2
rm -rf "$out" && mkdir -p "$out" || exit 1
"$render" "$@" -o "$out/one/f_%04d.png" --contact-sheet "$out/sheet_one.png" >/dev/null || exit 1
LP_NUM_THREADS=3 "$render" "$@" -o "$out/threads/f_%04d.png" >/dev/null || exit 1
"$render" "$@" --jobs 2 -o "$out/two/f_%04d.png" --contact-sheet "$out/sheet_two.png" >/dev/null || exit 1
"$render" "$@" --jobs 3 -o "$out/three/f_%04d.png" >/dev/null || exit 1
"$render" "$@" --jobs 3 --no-frames --contact-sheet "$out/sheet_three.png" >/dev/null || exit 1
for sheet in two three; do
    cmp "$out/sheet_one.png" "$out/sheet_$sheet.png" || { echo "the contact sheets differ ($sheet)" >&2; exit 1; }
done
count=0
for frame in "$out"/one/*.png; do
    name="$(basename "$frame")"
    for run in threads two three; do
        cmp "$frame" "$out/$run/$name" || { echo "$name differs between one process and '$run'" >&2; exit 1; }
    done
    count=$((count + 1))
done
[ "$count" -ge 2 ] || { echo "only $count frame(s) rendered" >&2; exit 1; }
first="$(ls "$out"/one/*.png | head -n 1)"
last="$(ls "$out"/one/*.png | tail -n 1)"
if cmp -s "$first" "$last"; then echo "the scene does not move: $first and $last are the same" >&2; exit 1; fi
echo "$count frames, the same bytes on 1 process (llvmpipe on its default and on 3 threads), 2 and 3 processes"
exit 0
