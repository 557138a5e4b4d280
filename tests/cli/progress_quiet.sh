#!/usr/bin/env bash
# Progress lines go to stderr only when it is a terminal and --quiet is not given: a pipe or a
# file never sees them; a terminal (faked with util-linux `script`) does, with --quiet it does
# not.
source "$(dirname "$0")/lib/common.sh" "$@"

run=("$ecorail" frontier --from A6 --to A7 --tmax 100 --step 1 --no-cache)
"${run[@]}" > out.txt 2> err.txt || { echo "FAIL: frontier"; fail=1; }
if [ -s err.txt ]; then echo "FAIL: stderr not a terminal, yet:"; cat err.txt; fail=1; fi

if command -v script > /dev/null; then
  script -qec "${run[*]} 2>&1 >/dev/null" /dev/null > tty.txt || { echo "FAIL: frontier on a tty"; fail=1; }
  grep -q "ecorail frontier: point [0-9]*/[0-9]*" tty.txt ||
    { echo "FAIL: no progress on a terminal"; cat -v tty.txt; fail=1; }
  script -qec "${run[*]} --quiet 2>&1 >/dev/null" /dev/null > quiet.txt ||
    { echo "FAIL: frontier --quiet on a tty"; fail=1; }
  if grep -q "ecorail frontier:" quiet.txt; then echo "FAIL: progress despite --quiet"; fail=1; fi
else
  echo "note: util-linux script is missing; the terminal half is skipped"
fi
exit $fail
