#!/usr/bin/env bash
# A run that misses its stop is never a result: `solve` at a running time where the engine's
# run comes to rest before the station (A6 -> A7 in 600 s; a journey A6 -> A8 in 1100 s) exits
# non-zero, says why, and writes no output file. A feasible run with the same outputs still
# writes them (so the check is not simply "never write").
source "$(dirname "$0")/lib/common.sh" "$@"

check_refused() {
  "$ecorail" "$@" --json out.json --csv out.csv > stdout.txt 2> stderr.txt
  local code=$?
  if [ "$code" -eq 0 ]; then
    echo "FAIL: exit 0 for a run that misses its stop: $*"; fail=1
  fi
  if ! grep -q "misses" stderr.txt; then
    echo "FAIL: no reason given: $*"; cat stderr.txt; fail=1
  fi
  if [ -e out.json ] || [ -e out.csv ]; then
    echo "FAIL: output written for a failed run: $*"; fail=1
    rm -f out.json out.csv
  fi
}

check_refused solve --from A6 --to A7 --time 600
check_refused solve --from A6 --to A8 --time 1100 --dwell 30

"$ecorail" solve --from A6 --to A7 --time 120 --json ok.json > /dev/null || {
  echo "FAIL: a feasible run failed"; fail=1
}
[ -s ok.json ] || { echo "FAIL: the feasible run wrote no JSON"; fail=1; }
exit $fail
