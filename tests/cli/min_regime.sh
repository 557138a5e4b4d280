#!/usr/bin/env bash
# --min-regime-m merges control phases shorter than the minimum, keeps the running time and the
# stop, and states what it cost against the unmerged optimum (small, and never a saving beyond
# the grid's noise, since the unmerged run is the optimum). A8 -> A9 in 130 s with the grid's own
# cruises (--cruise grid) has holds of 1-3 m between coasts on the descent (the default polishes
# them into one hold, with nothing left to merge).
source "$(dirname "$0")/lib/common.sh" "$@"

"$ecorail" solve --from A8 --to A9 --time 130 --cruise grid --quiet --json base.json > base.txt ||
  { echo "FAIL: base solve"; fail=1; }
"$ecorail" solve --from A8 --to A9 --time 130 --cruise grid --quiet --min-regime-m 20 --json m.json > m.txt ||
  { echo "FAIL: solve --min-regime-m"; cat m.txt; fail=1; }
grep -q "minimum regime 20 m" m.txt || { echo "FAIL: no minimum-regime line"; fail=1; }
python3 - <<'PY' || fail=1
import json
b, m = json.load(open("base.json")), json.load(open("m.json"))
assert abs(m["running_time_s"] - 130) <= 0.001, m["running_time_s"]
assert abs(m["stop_error_m"]) <= 0.5 and m["converged"]
r = m["min_regime"]
assert r["merged_phases"] > 0, r
assert abs(r["unmerged_energy_kJ"] - b["traction_input_energy_kJ"]) < 0.05, (r, b["traction_input_energy_kJ"])
assert abs(r["cost_kJ"] - (m["traction_input_energy_kJ"] - b["traction_input_energy_kJ"])) < 0.05
# Small: under 0.5 % here; a saving would mean the unmerged run was not the optimum.
assert -0.001 * b["traction_input_energy_kJ"] < r["cost_kJ"] < 0.005 * b["traction_input_energy_kJ"], r
assert all(s["end_m"] - s["start_m"] >= 20 for s in m["regimes"][:-1]), m["regimes"]
PY

# A minimum regime longer than the section: the merged run misses its time. The warning that
# says so comes with the brief report (no --full-report), the run exits non-zero and writes
# nothing.
"$ecorail" solve --from A6 --to A7 --time 110 --quiet --min-regime-m 2000 --json long.json \
  > long.txt 2> long.err
code=$?
[ "$code" -ne 0 ] || { echo "FAIL: a run that misses its time exited 0"; fail=1; }
grep -q "^  warning: running time .* misses the target 110.000 s" long.txt ||
  { echo "FAIL: no warning with the brief report"; cat long.txt; fail=1; }
[ ! -e long.json ] || { echo "FAIL: output written for a failed run"; fail=1; }
exit $fail
