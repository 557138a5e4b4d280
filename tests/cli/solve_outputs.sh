#!/usr/bin/env bash
# End-to-end: `ecorail solve` and `ecorail min-time` on the embedded line write every output,
# with the contract JSON keys and figures that meet the acceptance bounds; one and two threads
# give the same JSON (timing keys aside).
set -euo pipefail
ecorail="$1"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"

"$ecorail" solve --from A6 --to A7 --time 110 --json s.json --csv s.csv --xlsx s.xlsx \
  --plot s.svg --threads 2 > out.txt
grep -q "A6 -> A7" out.txt
grep -q "full_brake" out.txt
python3 - <<'PY'
import json, csv
j = json.load(open("s.json"))
for key in ["traction_energy_kJ", "regen_energy_kJ", "running_time_s", "target_time_s", "lambda",
            "distance_m", "stop_error_m", "max_overspeed_kmh", "solve_wall_s", "grid", "regimes"]:
    assert key in j, key
assert set(["ds_m", "dv_kmh"]) <= set(j["grid"]), j["grid"]
assert abs(j["running_time_s"] - 110) <= 0.1, j["running_time_s"]
assert abs(j["stop_error_m"]) <= 0.5
assert j["max_overspeed_kmh"] <= 0.05
assert j["distance_m"] == 1354
assert 30000 < j["traction_energy_kJ"] < 40000
kinds = [r["regime"] for r in j["regimes"]]
assert kinds[0] == "full_traction" and kinds[-1] == "full_brake", kinds
rows = list(csv.DictReader(open("s.csv")))
published = ["time_hms", "speed_cm_s", "speed_kmh", "accel_m_s2", "distance_m", "km_post_m",
             "gradient_permille", "traction_force_kN", "traction_power_kW"]
assert list(rows[0].keys())[:9] == published, list(rows[0].keys())
assert len(rows) == 110, len(rows)
assert float(rows[-1]["distance_m"]) == 1354.0 and float(rows[-1]["speed_kmh"]) == 0.0
assert float(rows[-1]["km_post_m"]) == 12240.0
# The +1.8 climb and the -3.5 descent appear in the travel direction.
grads = {float(r["gradient_permille"]) for r in rows}
assert {0.0, 1.8, -3.5} <= grads, grads
PY
head -c 4 s.xlsx | grep -q "PK" # a zip container
grep -q "<svg" s.svg

"$ecorail" solve --from A6 --to A7 --time 110 --json one.json --threads 1 > /dev/null
"$ecorail" solve --from A6 --to A7 --time 110 --json two.json --threads 2 > /dev/null
python3 - <<'PY'
import json
a, b = json.load(open("one.json")), json.load(open("two.json"))
for j in (a, b):
    j.pop("solve_wall_s"); j.pop("threads")
assert a == b, "JSON differs between 1 and 2 threads"
PY

"$ecorail" min-time --from A6 --to A7 --json m.json > /dev/null
python3 - <<'PY'
import json
m, s = json.load(open("m.json")), json.load(open("s.json"))
assert 80 < m["min_running_time_s"] < 90
assert abs(m["min_running_time_s"] - s["min_running_time_s"]) < 1e-9
assert m["traction_energy_kJ"] > s["traction_energy_kJ"]
PY
echo "solve_outputs: ok"
