#!/usr/bin/env bash
# Both ends of the running time, for every section of the reference line: a time below
# the flat-out run is refused (exit 2, the minimum stated, nothing written); a long time is either
# solved with a re-simulated run that stops at the station and keeps the time, or refused with
# the longest time the engine solves (exit 2, nothing written); an absurd time is refused. Never
# a run that misses its stop with exit 0. Journeys likewise.
set -uo pipefail
source "$(dirname "$0")/lib/common.sh" "$@"

stations=(A1 A2 A3 A4 A5 A6 A7 A8 A9 A10 A11 A12 A13 A14)

# check_result FILE TARGET: the JSON of a run that exited 0 keeps its stop and time.
check_result() {
  python3 - "$1" "$2" <<'PY' || { echo "FAIL: $1 (target $2 s) misses its stop or time"; fail=1; }
import json, sys
d = json.load(open(sys.argv[1]))
assert d["termination"] == "CONVERGENCE", d["termination"]
assert abs(d["stop_error_m"]) <= 0.5, d["stop_error_m"]
assert abs(d["running_time_s"] - float(sys.argv[2])) <= 0.1, d["running_time_s"]
PY
}

for i in $(seq 0 12); do
  from=${stations[$i]}
  to=${stations[$((i + 1))]}
  min=$("$ecorail" min-time --from "$from" --to "$to" | sed -n 's/.*minimum running time \([0-9.]*\) s.*/\1/p')
  [ -n "$min" ] || { echo "FAIL: no minimum for $from -> $to"; fail=1; continue; }
  short=$(python3 -c "print(round($min - 1, 3))")
  expect_error "minimum running time" solve --from "$from" --to "$to" --time "$short" --json o.json --csv o.csv
  expect_error "longest running time" solve --from "$from" --to "$to" --time 1000000 --json o.json --csv o.csv
  long=$(python3 -c "print(round(4 * $min))")
  "$ecorail" solve --from "$from" --to "$to" --time "$long" --json long.json > out.txt 2> err.txt
  code=$?
  if [ "$code" -eq 0 ]; then
    check_result long.json "$long"
  elif [ "$code" -ne 2 ] || ! grep -q "longest running time" err.txt || [ -e long.json ]; then
    echo "FAIL: $from -> $to in $long s: exit $code"; cat err.txt; fail=1
  fi
  rm -f long.json
done

# A journey at a long time: solved and kept, or refused; never a silent miss.
"$ecorail" solve --from A6 --to A8 --time 1100 --dwell 30 --json j.json > out.txt 2> err.txt
code=$?
if [ "$code" -eq 0 ]; then
  python3 - <<'PY' || { echo "FAIL: journey 1100 s"; fail=1; }
import json
d = json.load(open("j.json"))
assert d["termination"] == "CONVERGENCE", d["termination"]
assert abs(d["running_time_s"] - 1100) <= 0.1, d["running_time_s"]
for s in d["sections"]:
    assert abs(s["stop_error_m"]) <= 0.5, s["stop_error_m"]
PY
elif [ "$code" -ne 2 ] || [ -e j.json ]; then
  echo "FAIL: journey 1100 s exit $code"; cat err.txt; fail=1
fi

[ "$fail" -eq 0 ] && echo "both_time_ends: ok"
exit "$fail"
