#!/usr/bin/env bash
# Compiles every installed header of osgActor on its own: one translation unit per header that includes only it, as
# a user's first line would, against a copy of exactly the installed headers (so a header that leans on one that is
# not installed fails here too). Each must bring in what it needs and compile cleanly under strict warnings.
# Usage: compile_each_header.sh <compiler> <jobs> <source root> <header list file> [compiler flags...]
# The list holds one header a line, as a user includes it (osgActor/ActorNode). Exits 77 (skipped) when the compiler
# is not installed.
set -euo pipefail
compiler="$1" jobs="$2" root="$3" list="$4"
shift 4
if ! command -v "$compiler" >/dev/null 2>&1; then
    echo "$compiler is not installed: skipped"
    exit 77
fi
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
mkdir -p "$work/include" "$work/units"
printf '%s\n' "-I$work/include" "$@" >"$work/flags"
while read -r header; do
    [ -n "$header" ] || continue
    mkdir -p "$work/include/$(dirname "$header")"
    cp "$root/$header" "$work/include/$header"
    printf '#include <%s>\n' "$header" >"$work/units/$(echo "$header" | tr '/' '_').cpp"
done <"$list"
# The compiler on each unit, jobs at a time; every failure is printed, and any fails the test.
export compiler work
printf '%s\0' "$work"/units/*.cpp | xargs -0 -n 1 -P "$jobs" sh -c \
    'out=$("$compiler" @"$work/flags" -fsyntax-only "$1" 2>&1) ||
     { echo "FAILED: $(cat "$1")"; echo "$out"; exit 1; }' _
echo "$(grep -c . "$list") headers compile on their own with $compiler $*"
