#!/usr/bin/env bash
# The shipped log calibrates with the defaults: `calibrate --log
# data/contest/seed_profile_A6_A7_110s.csv` converges (its output-error fit needs more than 100
# Ceres iterations in a pass), writes the train and the JSON, and solve runs the calibrated
# train. A fit stopped by --max-iterations says which pass stopped and at what limit.
set -uo pipefail
source "$(dirname "$0")/lib/common.sh" "$@"

log="$src/data/contest/seed_profile_A6_A7_110s.csv"
"$ecorail" calibrate --log "$log" --out cal.toml --json cal.json --quiet > report.txt 2> err.txt ||
  { echo "FAIL: calibrate of the shipped log with the defaults"; cat err.txt; fail=1; }
/usr/bin/python3 - <<'PY' || fail=1
import json
j = json.load(open("cal.json"))
oe = j["formulations"]["output_error"]
assert oe["converged"] is True, oe.get("termination")
assert oe["termination"] == "CONVERGENCE", oe["termination"]
PY
"$ecorail" solve --from A6 --to A7 --time 110 --train cal.toml > /dev/null ||
  { echo "FAIL: solve refuses the calibrated train"; fail=1; }

"$ecorail" calibrate --log "$log" --max-iterations 5 --quiet > /dev/null 2> err.txt
[ $? -eq 1 ] || { echo "FAIL: a fit stopped at 5 iterations is not an error"; fail=1; }
grep -q "of at most 5 iterations" err.txt || { echo "FAIL: the limit is not named"; cat err.txt; fail=1; }
exit "$fail"
