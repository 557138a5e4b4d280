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
