#!/usr/bin/env bash
# A train slower than a line limit runs: the limit is capped at the train's maximum speed, the
# report and the JSON say so, the run never exceeds the train's maximum, and its flat-out time is
# longer than the faster train's.
source "$(dirname "$0")/lib/common.sh" "$@"

# The reference train with its maximum speed (and force curves) ending at 70 km/h.
sed -e 's/max_speed_kmh = 80.0/max_speed_kmh = 70.0/' \
    -e 's/to_kmh = 80.0, coeffs_kN = \[1343/to_kmh = 70.0, coeffs_kN = [1343/' \
    -e 's/{ from_kmh = 0.0, to_kmh = 77.0, coeffs_kN = \[166.0\] },/{ from_kmh = 0.0, to_kmh = 70.0, coeffs_kN = [166.0] },/' \
    -e '/from_kmh = 77.0/d' "$src/data/contest/train.toml" > slow.toml
grep -q "max_speed_kmh = 70.0" slow.toml || { echo "FAIL: could not make the slow train"; exit 1; }

"$ecorail" min-time --from A6 --to A7 --train slow.toml --json slow_min.json > slow_min.txt ||
  { echo "FAIL: min-time with the slow train"; cat slow_min.txt; fail=1; }
"$ecorail" min-time --from A6 --to A7 --json fast_min.json > /dev/null || fail=1
"$ecorail" solve --from A6 --to A7 --time 100 --train slow.toml --json s.json --csv s.csv > s.txt ||
  { echo "FAIL: solve with the slow train"; cat s.txt; fail=1; }
grep -q "note: line limits up to 80.0 km/h are above the train's maximum speed and capped at 70.0 km/h" s.txt ||
  { echo "FAIL: the report does not say the limits were capped"; cat s.txt; fail=1; }
python3 - <<'PY' || fail=1
import json, csv
s = json.load(open("s.json"))
assert any("capped at 70.0 km/h" in n for n in s["notes"]), s["notes"]
assert abs(s["running_time_s"] - 100) <= 0.1 and abs(s["stop_error_m"]) <= 0.5
top = max(float(r["speed_kmh"]) for r in csv.DictReader(open("s.csv")))
assert top <= 70.0 + 1e-6, top
assert max(float(r["speed_limit_kmh"]) for r in csv.DictReader(open("s.csv"))) <= 70.0 + 1e-6
slow, fast = json.load(open("slow_min.json")), json.load(open("fast_min.json"))
assert slow["running_time_s"] > fast["running_time_s"] + 0.5, (slow["running_time_s"], fast["running_time_s"])
PY
exit $fail
