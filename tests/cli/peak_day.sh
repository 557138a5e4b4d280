#!/usr/bin/env bash
# Question 2.2 end to end on a small line (A6 -> A9): peak windows make headway classes by the
# clock. Too few trains for the windows is one clear error; headways that break a class are
# named; every output (CSV, XLSX, JSON, and the optimiser's results in both models) keeps the
# classes; the separation check runs every train together, reports its margin, never finds the
# cap exceeded, and writes the speed-distance profiles (long CSV, SVG) with the cap.
set -uo pipefail
source "$(dirname "$0")/lib/common.sh" "$@"

day=(--from A6 --to A9 --trip-time 480 --span 3000 --peak 600:1200 --peak 2000:2400
     --peak-headway 120:150 --offpeak-headway 300:660)

expect_error "peak window 1 (600-1200 s) needs at least 4 peak headways" \
  timetable evaluate "${day[@]}" --trains 5 --json x.json
expect_error "--peak" timetable evaluate --from A6 --to A9 --trip-time 480 --trains 6 --span 1000 \
  --headway 150:250 --peak-headway 120:150 --json x.json
expect_error "--peak" timetable evaluate "${day[@]}" --trains 16 --peak 900:800 --json x.json
# 300 s from 600 s: a peak headway (it overlaps 600-1200 s) outside 120-150 s.
python3 -c "print('headway_s'); print('\n'.join(['300'] * 3 + ['175'] * 12))" > flat.csv
expect_error "a peak headway" timetable evaluate "${day[@]}" --trains 16 --headways flat.csv --json x.json

# Classes in every output: uniform (evaluate), power-flow optimum, overlap optimum (exact DP).
"$ecorail" timetable evaluate "${day[@]}" --trains 16 --json uni.json --csv uni.csv --xlsx uni.xlsx \
  --diagram uni.svg --window 0:3600 > uni.txt || { echo "FAIL: evaluate"; fail=1; }
"$ecorail" timetable optimise "${day[@]}" --trains 16 --moves 20000 --json opt.json --csv opt.csv \
  --xlsx opt.xlsx --separation --profiles prof.csv --profile-plot prof.svg > opt.txt \
  || { echo "FAIL: optimise"; cat opt.txt; fail=1; }
"$ecorail" timetable optimise "${day[@]}" --trains 16 --model overlap --json ov.json --csv ov.csv \
  > ov.txt || { echo "FAIL: optimise overlap"; fail=1; }
for f in uni.json uni.csv uni.xlsx uni.svg opt.json opt.csv opt.xlsx prof.csv prof.svg ov.json ov.csv; do
  [ -s "$f" ] || { echo "FAIL: $f not written"; fail=1; }
done
grep -q "rgb(253, 224, 197)" uni.svg || { echo "FAIL: peak windows not shaded in the diagram"; fail=1; }
python3 - <<'PY' || fail=1
import csv, json, re, zipfile
windows, peak, off = [(600, 1200), (2000, 2400)], (120, 150), (300, 660)
def check(t, what):
    assert t[0] == 0 and t[-1] == 3000 and len(t) == 16, (what, t)
    for a, b in zip(t, t[1:]):
        lo, hi = peak if any(a < w1 and b > w0 for w0, w1 in windows) else off
        assert lo <= b - a <= hi, (what, a, b)
def from_csv(name):
    rows = [r for r in csv.DictReader(open(name)) if r["station"] == "A6"]
    return [round(float(r["departure_s"])) for r in rows]
def from_xlsx(name):
    z = zipfile.ZipFile(name)
    sheet = z.read("xl/worksheets/sheet1.xml").decode()
    # the departure_s column is E, as in the CSV; every train's first row is its A6 departure
    cells = dict(re.findall(r'<c r="([A-Z]+\d+)"[^>]*>(?:<f>[^<]*</f>)?<v>([^<]*)</v>', sheet))
    # row 1 is the header (shared strings)
    rows = sorted(int(k[1:]) for k in cells if k.startswith("A") and k[1:].isdigit() and k != "A1")
    deps, seen = [], set()
    for r in rows:
        train = cells.get("A%d" % r)
        if train is not None and train not in seen:
            seen.add(train)
            deps.append(round(float(cells["E%d" % r])))
    return deps
for name in ["uni", "opt", "ov"]:
    j = json.load(open(name + ".json"))
    check(j["departures_s"], name + ".json")
    t = j["departures_s"]
    cls = ["peak" if any(a < w1 and b > w0 for w0, w1 in windows) else "offpeak" for a, b in zip(t, t[1:])]
    assert j["headway_classes"] == cls, name
    check(from_csv(name + ".csv"), name + ".csv")
for name in ["uni", "opt"]:
    check(from_xlsx(name + ".xlsx"), name + ".xlsx")
o, u = json.load(open("opt.json")), json.load(open("uni.json"))
assert o["substation_energy_kJ"] <= u["substation_energy_kJ"] + 1e-6
s = o["separation"]
assert s["min_speed_margin_kmh"] > 0 and not s["cap_exceeded"] and not s["cap_binds_at_plan"], s
rows = list(csv.DictReader(open("prof.csv")))
assert {int(r["train"]) for r in rows} == set(range(1, 17))
for r in rows:
    if r["separation_cap_kmh"]:
        assert float(r["speed_kmh"]) <= float(r["separation_cap_kmh"]) + 1e-3, r
    assert float(r["speed_kmh"]) <= float(r["line_limit_kmh"]) + 0.5, r
PY
exit $fail
