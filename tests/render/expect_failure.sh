#!/bin/sh
# expect_failure.sh <regex> <command...>: passes when the command exits with status 1..127 (a clean failure, not a
# crash by signal) and its standard error matches the extended regular expression.
regex="$1"
shift
err="$("$@" 2>&1 >/dev/null)"
status=$?
printf '%s\n' "$err"
if [ "$status" -eq 0 ]; then echo "expect_failure: the command succeeded" >&2; exit 1; fi
if [ "$status" -ge 128 ]; then echo "expect_failure: the command crashed (status $status)" >&2; exit 1; fi
printf '%s\n' "$err" | grep -Eq -- "$regex" || { echo "expect_failure: no message matching /$regex/" >&2; exit 1; }
exit 0
