#!/usr/bin/env bash
# End-to-end: journeys through `ecorail solve` (dwell syntax, optimal and proportional split,
# per-second table through the dwell) and `ecorail frontier` (outputs and the cache).
set -euo pipefail
ecorail="$1"
work=$(mktemp -d)
[ -n "${KEEP:-}" ] || trap 'rm -rf "$work"' EXIT
cd "$work"

"$ecorail" solve --from A6 --to A8 --time 220 --dwell A7=45 --json opt.json --csv opt.csv \
  --plot opt.svg > opt.txt
"$ecorail" solve --from A6 --to A8 --time 220 --dwell 45 --split proportional --json prop.json \
  > prop.txt
python3 - <<'PY'
import json, csv
o, p = json.load(open("opt.json")), json.load(open("prop.json"))
assert o["split"] == "optimal" and p["split"] == "proportional"
assert abs(o["running_time_s"] - 220) <= 0.1 and abs(p["running_time_s"] - 220) <= 0.1
assert len(o["sections"]) == 2 and len(o["section_times_s"]) == 2
assert o["stops"] == ["A6", "A7", "A8"]
assert o["dwells"] == [{"station": "A7", "dwell_s": 45.0}]
assert abs(o["trip_time_s"] - 265) <= 0.1
assert o["traction_energy_kJ"] <= p["traction_energy_kJ"]
for s in o["sections"]:
    assert abs(s["marginal_vs_lambda"]) < 0.05, s["marginal_vs_lambda"]
    assert abs(s["stop_error_m"]) < 0.5
assert o["equal_lambda"]["max_relative_deviation"] < 0.05
assert abs(sum(s["traction_energy_kJ"] for s in o["sections"]) - o["traction_energy_kJ"]) < 1e-6
rows = list(csv.DictReader(open("opt.csv")))
assert abs(len(rows) - 265) <= 1, len(rows)
dwelling = [r for r in rows if r["dwelling"] == "1"]
assert 44 <= len(dwelling) <= 46, len(dwelling)
assert all(float(r["speed_kmh"]) == 0 for r in dwelling)
assert float(rows[-1]["distance_m"]) == 2634.0
PY

# Dwell errors: a stop that is not intermediate, a malformed value, a missing dwell.
for args in "--dwell A9=30" "--dwell A7=abc" ""; do
  set +e
  "$ecorail" solve --from A6 --to A8 --time 220 $args --json bad.json > /dev/null 2> err.txt
  code=$?
  set -e
  [ "$code" -eq 2 ] || { echo "FAIL: '$args' exit $code"; exit 1; }
  grep -q -- "--dwell" err.txt || { echo "FAIL: '$args' message"; cat err.txt; exit 1; }
  [ ! -e bad.json ] || { echo "FAIL: output left behind"; exit 1; }
done

# Frontier: outputs, monotone, and the cache gives the same answer on the second call.
"$ecorail" frontier --from A9 --to A10 --tmax 92 --step 2 --cache-dir cache --json f1.json \
  --csv f1.csv --plot f1.svg > f1.txt
ls cache/*.json > /dev/null
"$ecorail" frontier --from A9 --to A10 --tmax 92 --step 2 --cache-dir cache --json f2.json > /dev/null
python3 - <<'PY'
import json, csv
a, b = json.load(open("f1.json")), json.load(open("f2.json"))
assert a["points"] == b["points"], "cache changed the answer"
pts = a["points"]
assert len(pts) >= 10 and a["monotone"]
assert all(x["cost_kJ"] > y["cost_kJ"] for x, y in zip(pts, pts[1:]))
rows = list(csv.DictReader(open("f1.csv")))
assert len(rows) == len(pts)
PY
grep -q "<svg" f1.svg
echo "journey_frontier: ok"
