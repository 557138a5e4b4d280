#!/usr/bin/env bash
# `ecorail delay` end to end on a small plan (A6 -> A9, three trains 300 s apart, 380 s trip, written by
# `ecorail timetable evaluate --csv`): a delay recovered at the next station writes JSON, CSV
# and SVG with the documented keys and sane values; a delay no station absorbs exits 0 with a
# warning, back_on_time_at null and the final lateness; --lateness-first beside energy first;
# bad input exits 2 with one line and no file left behind.
set -uo pipefail
source "$(dirname "$0")/lib/common.sh" "$@"
export XDG_CACHE_HOME="$work/xdg"
mkdir -p "$XDG_CACHE_HOME"
cache=(--cache-dir "$work/cache" --frontier-span 30)

"$ecorail" timetable evaluate --from A6 --to A9 --trip-time 380 --trains 3 --span 600 \
  --headway 120:660 --csv plan.csv --quiet > /dev/null || { echo "FAIL: plan"; fail=1; }

"$ecorail" delay --plan plan.csv --train 2 --station A7 --delay 10 "${cache[@]}" \
  --json d.json --csv d.csv --svg d.svg > d.txt || { echo "FAIL: delay"; cat d.txt; fail=1; }
for f in d.json d.csv d.svg; do [ -s "$f" ] || { echo "FAIL: $f not written"; fail=1; }; done
grep -q "back on time at A8" d.txt || { echo "FAIL: report lacks the station"; cat d.txt; fail=1; }
grep -q "follower train 3 behind train 2: not affected" d.txt \
  || { echo "FAIL: report lacks the follower"; cat d.txt; fail=1; }
python3 - <<'PY' || fail=1
import csv, json
d = json.load(open("d.json"))
for k in ["back_on_time_at", "final_lateness_s", "recovery_energy_kJ", "plan_energy_kJ",
          "rule_energy_kJ", "sections", "trains", "followers", "provenance", "termination"]:
    assert k in d, k
assert d["back_on_time_at"] == "A8", d["back_on_time_at"]
assert d["recovered"] is True and d["termination"] == "CONVERGENCE"
assert 0 <= d["final_lateness_s"] <= 0.05, d["final_lateness_s"]
assert d["recovery_energy_kJ"] > d["plan_energy_kJ"] > 0
assert d["rule_energy_kJ"] >= d["recovery_energy_kJ"] * (1 - 1e-4)
s = d["sections"]
assert len(s) == 1 and s[0]["from"] == "A7" and s[0]["to"] == "A8", s
x = s[0]
for k in ["planned_time_s", "new_time_s", "rule_time_s", "plan_energy_kJ", "new_energy_kJ",
          "rule_energy_kJ", "new_dwell_s"]:
    assert k in x, k
assert x["min_time_s"] <= x["new_time_s"] < x["planned_time_s"]
assert abs(x["planned_time_s"] - x["new_time_s"] - 10.0) < 0.01, x
assert abs(sum(t["new_energy_kJ"] for t in s) - d["recovery_energy_kJ"]) < 1e-6
assert d["trains"][0]["train"] == 2 and d["trains"][0]["back_on_time_at"] == "A8"
assert d["trains"][0]["never_late"] is False and d["trains"][0]["max_lateness_s"] == 10
f = d["followers"]
assert len(f) == 1 and f[0]["train"] == 3 and not f[0]["affected"], f
assert f[0]["min_speed_margin_kmh"] > 0 and d["min_follower_margin_kmh"] > 0
rows = list(csv.DictReader(open("d.csv")))
assert len(rows) == 1 and rows[0]["from"] == "A7", rows
assert abs(float(rows[0]["new_energy_kJ"]) - x["new_energy_kJ"]) < 0.06
assert open("d.svg").read().lstrip().startswith("<?xml") or "<svg" in open("d.svg").read()
PY

# A delay no station absorbs: exit 0, a warning, back_on_time_at null, the final lateness.
"$ecorail" delay --plan plan.csv --train 1 --station A8 --delay 200 "${cache[@]}" \
  --json late.json > late.txt || { echo "FAIL: unrecoverable delay exits non-zero"; fail=1; }
grep -q "warning: a delay of 200.00 s at A8 cannot be recovered" late.txt \
  || { echo "FAIL: no warning"; cat late.txt; fail=1; }
python3 - <<'PY' || fail=1
import json
d = json.load(open("late.json"))
assert d["back_on_time_at"] is None and d["recovered"] is False
s = d["sections"]
assert len(s) == 1 and s[0]["flat_out"] is True
late = 200 - (s[0]["planned_time_s"] - s[0]["min_time_s"])
assert abs(d["final_lateness_s"] - late) < 0.01, (d["final_lateness_s"], late)
assert d["warnings"], d
PY

# Bad input: exit 2, one line, nothing written.
expect_error "--station" delay --plan plan.csv --train 1 --station A99 --delay 10 --json x.json
expect_error "--station" delay --plan plan.csv --train 1 --station A9 --delay 10 --json x.json
expect_error "--train" delay --plan plan.csv --train 4 --station A7 --delay 10 --json x.json
expect_error "--train" delay --plan plan.csv --train 0 --station A7 --delay 10 --json x.json
expect_error "--delay" delay --plan plan.csv --train 1 --station A7 --delay -5 --json x.json
expect_error "--delay" delay --plan plan.csv --train 1 --station A7 --delay nan --json x.json
expect_error "--plan/--reference" delay --train 1 --station A7 --delay 10 --json x.json
expect_error "--plan/--reference" delay --plan plan.csv --reference --train 1 --station A7 \
  --delay 10 --json x.json
expect_error "nothere.csv" delay --plan nothere.csv --train 1 --station A7 --delay 10 --json x.json
expect_error "--station" delay --reference --train 1 --station A14 --delay 10 --json x.json
expect_error "--svg" delay --plan plan.csv --train 1 --station A7 --delay 10 --svg x.png
# Train 1 departs A7 before it arrives there.
awk -F, 'BEGIN{OFS=","} NR==3{$4=$5+1} {print}' plan.csv > broken.csv
expect_error "broken.csv" delay --plan broken.csv --train 1 --station A7 --delay 10 --json x.json
# A delay far longer than the headway (the case where a follower could end inside the late
# train and pass it): trains 120 s apart, train 1 leaves A7 5000 s late. Every follower waits at a
# stop for the line ahead to clear, never comes closer than its braking distance, never arrives
# anywhere before the train ahead, and the cascade is reported.
"$ecorail" timetable evaluate --from A6 --to A9 --trip-time 380 --trains 3 --span 240 \
  --headway 120:660 --csv close.csv --quiet > /dev/null || { echo "FAIL: close plan"; fail=1; }
"$ecorail" delay --plan close.csv --train 1 --station A7 --delay 5000 --followers 2 \
  "${cache[@]}" --json long.json > long.txt 2> long_err.txt \
  || { echo "FAIL: long delay"; cat long.txt long_err.txt; fail=1; }
# Off a terminal, one line per stage on stderr (nothing with --quiet).
grep -qx "ecorail delay: recovery" long_err.txt && grep -qx "ecorail delay: follower" long_err.txt \
  || { echo "FAIL: no stage lines off a terminal"; cat long_err.txt; fail=1; }
python3 - <<'PY' || fail=1
import csv, json
d = json.load(open("long.json"))
plan = {}
for row in csv.DictReader(open("close.csv")):
    plan.setdefault(int(row["train"]), {})[row["station"]] = float(row["arrival_s"])
f = d["followers"]
assert len(f) == 2 and all(x["affected"] for x in f), f
for x in f:
    assert x["min_gap_m"] >= 0.0, x
    assert x["min_distance_margin_m"] >= -0.01, x
    assert x["min_speed_margin_kmh"] >= -1e-3, x
    assert x["station_wait_s"] > 4000, x
trains = {t["train"]: t for t in d["trains"]}
assert sorted(trains) == [1, 2, 3], trains
stations = d["stations"]
for j, st in enumerate(stations[1:], start=1):
    arrive = [plan[k][st] + trains[k]["lateness_s"][j] for k in (1, 2, 3)]
    assert arrive[0] < arrive[1] < arrive[2], (st, arrive)
c = d["cascade"]
assert c["held_up_trains"] == 2 and c["ends"] is False and c["plan_absorbs"] is False, c
assert c["final_lateness_s"] > 4000, c
assert any("cannot absorb" in w for w in d["warnings"]), d["warnings"]
PY
# Lateness first (--lateness-first) beside energy first on the 120 s plan: the mode is named,
# its total lateness is no more than energy first's, which is reported beside it and is the
# default run's; every follower keeps its braking distance.
"$ecorail" delay --plan close.csv --train 1 --station A7 --delay 60 --followers 2 "${cache[@]}" \
  --quiet --json ef.json > /dev/null || { echo "FAIL: energy first"; fail=1; }
"$ecorail" delay --plan close.csv --train 1 --station A7 --delay 60 --followers 2 "${cache[@]}" \
  --quiet --lateness-first --json lf.json > /dev/null || { echo "FAIL: lateness first"; fail=1; }
python3 - <<'PY' || fail=1
import json
ef, lf = json.load(open("ef.json")), json.load(open("lf.json"))
assert ef["recovery_mode"] == "energy-first" and ef["energy_first_energy_kJ"] is None, ef
assert lf["recovery_mode"] == "lateness-first" and "lateness_first" in lf, lf
assert lf["total_lateness_s"] <= lf["energy_first_total_lateness_s"] + 0.05, lf
assert abs(lf["energy_first_total_lateness_s"] - ef["total_lateness_s"]) < 1e-6, (lf, ef)
assert abs(lf["energy_first_energy_kJ"] - ef["recovery_energy_kJ"]) < 1e-6, (lf, ef)
for d in (ef, lf):
    for x in d["followers"]:
        assert x["min_distance_margin_m"] >= -0.01 and x["traction_kJ"] > 0, x
PY
# The delay is bounded, with a clear error (it was accepted up to 86400 s and silently capped).
expect_error "--delay" delay --plan plan.csv --train 1 --station A7 --delay 20000 --json x.json
expect_error "--delay" delay --plan plan.csv --train 1 --station A7 --delay 86400 --json x.json
exit $fail
