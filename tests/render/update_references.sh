#!/bin/sh
# update_references.sh <osgactorrender> <folder> <reference folder> <scene> <changed scene> <options...>:
# --update-references makes missing references, says so, and keeps matching ones; after the scene changed it
# rewrites exactly the frames that changed, and the changed scene then matches them.
render="$1"
out="$2"
committed="$3"
scene="$4"
changed="$5"
shift 5
refs="$out/refs/f_%04d.png"
rm -rf "$out" && mkdir -p "$out" || exit 1
expect() { # expect <status> <regex> <command...>
    status="$1"; regex="$2"; shift 2
    output="$("$@" 2>&1)"; got=$?
    printf '%s\n' "$output"
    [ "$got" -eq "$status" ] || { echo "status $got, expected $status" >&2; exit 1; }
    printf '%s\n' "$output" | grep -Eq -- "$regex" || { echo "no output matching /$regex/" >&2; exit 1; }
}
expect 0 "updated 4 of 4 references .*\(0 changed, 4 new" "$render" "$scene" "$@" --compare "$refs" --update-references
for i in 0 1 2 3; do
    cmp "$out/refs/f_000$i.png" "$committed/two_boxes_000$i.png" || { echo "new reference $i differs" >&2; exit 1; }
done
expect 0 "updated 0 of 4 references" "$render" "$scene" "$@" --compare "$refs" --update-references
expect 1 "4 of 4 frames differ" "$render" "$changed" "$@" --compare "$refs"
expect 0 "updated 4 of 4 references .*\(4 changed, 0 new" "$render" "$changed" "$@" --compare "$refs" --update-references
expect 0 "all 4 frames match" "$render" "$changed" "$@" --compare "$refs"
expect 1 "4 of 4 frames differ" "$render" "$scene" "$@" --compare "$refs"
exit 0
