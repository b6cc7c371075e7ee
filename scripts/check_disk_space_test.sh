#!/usr/bin/env bash
# Test of scripts/check_disk_space.sh (CTest "scripts/check_disk_space"): silent above the bar, a warning naming the
# folder and its free space below it, never a failure; a bar that is no number is an error.
set -euo pipefail
script="$(cd "$(dirname "$0")" && pwd)/check_disk_space.sh"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0
fail() { echo "FAIL $1"; sed 's/^/  | /' "$work/err"; failures=$((failures + 1)); }

AMOS_MIN_FREE_GIB=0 bash "$script" "$work" 2> "$work/err" || fail "a bar of 0 GiB fails"
[[ ! -s "$work/err" ]] && echo "ok   silent above the bar" || fail "warns above the bar"

AMOS_MIN_FREE_GIB=1000000000 bash "$script" "$work" 2> "$work/err" && echo "ok   exits 0 below the bar" ||
  fail "fails below the bar"
grep -q "^warning: $work has [0-9]* MiB free; a fresh set-up needs about 1000000000 GiB" "$work/err" &&
  echo "ok   the warning names the folder, its free space and the bar" || fail "no warning naming the folder"

if AMOS_MIN_FREE_GIB=lots bash "$script" "$work" 2> "$work/err"; then
  fail "a bar that is no number is accepted"
else
  grep -q "AMOS_MIN_FREE_GIB must be a whole number of GiB, not 'lots'" "$work/err" &&
    echo "ok   a bar that is no number is an error naming it" || fail "the error does not name the bar"
fi
exit $((failures > 0))
