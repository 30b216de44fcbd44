#!/bin/sh
# expect_output_file.sh <file> <command...>: removes the file, runs the command, and passes when the command exits
# with status 0 and has written the file (not empty).
file="$1"
shift
rm -f "$file"
"$@" || { echo "expect_output_file: the command failed (status $?)" >&2; exit 1; }
[ -s "$file" ] || { echo "expect_output_file: $file was not written" >&2; exit 1; }
exit 0
