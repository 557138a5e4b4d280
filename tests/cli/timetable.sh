#!/usr/bin/env bash
# `ecorail timetable`: bad input is one clear error with exit 2 and nothing written; a run
# writes its timetable, energy JSON (the keys docs/fleet.md promises), XLSX and plots, and the
# optimum is no worse than the timetable it started from.
set -uo pipefail
source "$(dirname "$0")/lib/common.sh" "$@"

small=(--from A6 --to A9 --trains 6 --span 1000 --headway 150:250 --trip-time 480)
outs=(--json out.json --csv out.csv --xlsx out.xlsx --diagram d.svg)

printf 'headway_s\n200\n200\n200\n200\n100\n' > low.csv
expect_error "low.csv: row 6, field 'headway_s'" timetable evaluate "${small[@]}" --headways low.csv "${outs[@]}"
printf 'headway_s\n200\n200\n200\n200\n190\n' > short.csv
expect_error "not the span 1000 s" timetable evaluate "${small[@]}" --headways short.csv "${outs[@]}"
printf 'headway_s\n200\n200\nabc\n200\n200\n' > text.csv
expect_error "text.csv: row 4" timetable evaluate "${small[@]}" --headways text.csv "${outs[@]}"
expect_error "--dwell" timetable evaluate "${small[@]}" --dwell 50 "${outs[@]}"
expect_error "--model" timetable evaluate "${small[@]}" --model magic "${outs[@]}"
expect_error "--step" timetable evaluate "${small[@]}" --step 0.3 "${outs[@]}"
expect_error "span_s" timetable optimise --from A6 --to A9 --trains 6 --span 5000 --headway 150:250 --trip-time 480 "${outs[@]}"
expect_error "flat-out running time" timetable evaluate --from A6 --to A9 --trains 6 --span 1000 --headway 150:250 --trip-time 200 "${outs[@]}"
expect_error "--uniform" timetable evaluate "${small[@]}" --uniform --headways low.csv "${outs[@]}"
expect_error "--sections-at" timetable evaluate "${small[@]}" --model sections "${outs[@]}"
expect_error "--per-train-patterns" timetable optimise "${small[@]}" --per-train-patterns --model overlap "${outs[@]}"
expect_error "--per-train-patterns" timetable optimise "${small[@]}" --per-train-patterns --optimise headways "${outs[@]}"

# A good run: every output, headways within bounds, the optimum no worse than uniform.
"$ecorail" timetable evaluate "${small[@]}" --json uni.json > /dev/null || { echo "FAIL: evaluate"; fail=1; }
"$ecorail" timetable optimise "${small[@]}" "${outs[@]}" --power-plot p.svg --window 0:1500 \
  > opt.txt || { echo "FAIL: optimise"; fail=1; }
for f in out.json out.csv out.xlsx d.svg p.svg; do
  [ -s "$f" ] || { echo "FAIL: $f not written"; fail=1; }
done
python3 - <<'PY' || fail=1
import json, csv
u, o = json.load(open("uni.json")), json.load(open("out.json"))
for key in ["substation_energy_kJ", "traction_energy_kJ", "regen_energy_kJ", "used_regen_kJ",
            "model", "time_step_s", "headways_s", "bound_used_regen_kJ"]:
    assert key in o, "missing key " + key
h = o["headways_s"]
assert len(h) == 5 and sum(h) == 1000 and all(150 <= x <= 250 for x in h), h
assert o["substation_energy_kJ"] <= u["substation_energy_kJ"] + 1e-6, (o, u)
assert o["bound_used_regen_kJ"] >= o["used_regen_kJ"]
assert abs(o["traction_energy_kJ"] - o["substation_energy_kJ"] - o["used_regen_kJ"]) < 1e-6 * o["traction_energy_kJ"]
rows = list(csv.DictReader(open("out.csv")))
assert len(rows) == 6 * 4, len(rows)  # one row per train and stop
for r in rows:
    assert float(r["departure_s"]) >= float(r["arrival_s"])
PY
# Per-train patterns: every train's rows in the timetable follow its own pattern (dwells in
# range, trip time kept), and the result is no worse than one pattern for all.
"$ecorail" timetable optimise "${small[@]}" --per-train-patterns --moves 20000 --json pt.json \
  --csv pt.csv > pt.txt || { echo "FAIL: optimise --per-train-patterns"; fail=1; }
python3 - <<'PY' || fail=1
import json, csv
o = json.load(open("pt.json"))
ps, s = o["patterns_per_train"], o["pattern_search"]
assert len(ps) == 6 and s["per_train_patterns"], s
assert o["substation_energy_kJ"] <= s["common_pattern_substation_energy_kJ"] + 1e-6, s
rows = list(csv.DictReader(open("pt.csv")))
for p in ps:
    mine = [r for r in rows if int(r["train"]) == p["train"]]
    assert len(mine) == 4, mine
    assert abs(p["trip_time_s"] - 480) < 0.05, p
    for j, d in enumerate(p["dwells_s"]):
        assert 30 - 1e-9 <= d <= 45 + 1e-9, p
        r = mine[j + 1]
        assert abs(float(r["departure_s"]) - float(r["arrival_s"]) - d) < 0.01, (r, d)
    for j, t in enumerate(p["running_times_s"]):
        assert abs(float(mine[j + 1]["arrival_s"]) - float(mine[j]["departure_s"]) - t) < 0.06, (mine, t)
PY
# A station whose name would run a command in gnuplot is drawn as text on the train diagram.
mkdir line
cp "$src"/data/contest/*.csv line/
sed -i "s/^A7,/A7';system('touch X');print('%,/" line/stations.csv
"$ecorail" timetable evaluate "${small[@]}" --line line --diagram inj.svg > /dev/null 2> err.txt ||
  { echo "FAIL: diagram with a quoted station name"; cat err.txt; fail=1; }
[ -e X ] && { echo "FAIL: a station name ran a command"; fail=1; }
grep -q "system" inj.svg || { echo "FAIL: the station name is not drawn"; fail=1; }

[ "$fail" -eq 0 ] && echo "timetable: ok"
exit "$fail"
