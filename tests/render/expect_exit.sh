#!/bin/sh
# expect_exit.sh <status> <regex> <command...>: passes when the command exits with exactly that status and its
# standard output and error together match the extended regular expression.
expected="$1"
regex="$2"
shift 2
output="$("$@" 2>&1)"
status=$?
printf '%s\n' "$output"
if [ "$status" -ne "$expected" ]; then echo "expect_exit: status $status, expected $expected" >&2; exit 1; fi
printf '%s\n' "$output" | grep -Eq -- "$regex" || { echo "expect_exit: no output matching /$regex/" >&2; exit 1; }
exit 0
