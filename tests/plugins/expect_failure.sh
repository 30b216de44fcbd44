#!/bin/sh
# expect_failure.sh <expected text> <command...>: passes when the command fails and its output contains the text.
expected="$1"
shift
output=$("$@" 2>&1)
status=$?
printf '%s\n' "$output"
if [ "$status" -eq 0 ]; then
    echo "expect_failure: the command succeeded" >&2
    exit 1
fi
case "$output" in
    *"$expected"*) exit 0 ;;
    *) echo "expect_failure: the output does not contain: $expected" >&2; exit 1 ;;
esac
