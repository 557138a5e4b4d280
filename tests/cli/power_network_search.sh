#!/usr/bin/env bash
# `ecorail timetable optimise --model network` beyond plain headways: the pattern search
# (--optimise pattern) is never worse than the headways alone and keeps the trip time and the
# dwell range; --per-train-patterns is one clear error naming why; a day with peak windows is
# evaluated and optimised with every headway in its class (checked on the outputs), and
# `evaluate --headways` of the optimum's headways gives its energy; the summary's bound is never
# above the energy found (also on the reference day); every run writes the network's JSON keys.
set -uo pipefail
source "$(dirname "$0")/lib/common.sh" "$@"

supply="$src/data/contest/power_supply.toml"
net=(--model network --power-supply "$supply" --step 0.5)
small=(--from A6 --to A9 --trains 6 --span 1000 --headway 150:250 --trip-time 480)
cheap=(--restarts 1 --moves 200 --quiet)

expect_error "network balance lays one trip under every train" \
  timetable optimise "${small[@]}" "${net[@]}" --per-train-patterns --json x.json

"$ecorail" timetable optimise "${small[@]}" "${net[@]}" "${cheap[@]}" --optimise pattern \
  --json pat.json > pat.txt || { echo "FAIL: pattern search"; cat pat.txt; fail=1; }

day=(--from A6 --to A9 --trip-time 480 --span 3000 --peak 600:1200 --peak 2000:2400
     --peak-headway 120:150 --offpeak-headway 300:660 --trains 16)
"$ecorail" timetable evaluate "${day[@]}" "${net[@]}" --json wuni.json > wuni.txt ||
  { echo "FAIL: windowed evaluate"; cat wuni.txt; fail=1; }
"$ecorail" timetable optimise "${day[@]}" "${net[@]}" "${cheap[@]}" --json wopt.json --csv wopt.csv \
  > wopt.txt || { echo "FAIL: windowed optimise"; cat wopt.txt; fail=1; }
python3 -c "
import json
print('headway_s')
print('\n'.join(str(h) for h in json.load(open('wopt.json'))['headways_s']))" > wopt_headways.csv
"$ecorail" timetable evaluate "${day[@]}" "${net[@]}" --headways wopt_headways.csv --json wre.json \
  > wre.txt || { echo "FAIL: windowed re-evaluate"; cat wre.txt; fail=1; }

# The reference day (100 trains, 0.1 s): the bound is below what the optimiser finds (a short
# run: no annealing, the polish stopped after 3 s).
"$ecorail" timetable optimise --model network --power-supply "$supply" --restarts 0 --time-limit 3 \
  --quiet --json ref.json > ref.txt || { echo "FAIL: reference optimise"; cat ref.txt; fail=1; }

python3 - <<'PY' || fail=1
import csv, json
def network_keys(j, what):
    for key in ["substations", "line_losses_kJ", "traction_input_kJ", "auxiliary_kJ",
                "used_regen_kJ", "curtailed_regen_kJ", "min_train_voltage_V", "max_train_voltage_V"]:
        assert key in j, (what, "missing key " + key)
    for s in j["substations"]:
        for key in ["name", "position_m", "energy_kJ", "peak_power_kW", "peak_current_A"]:
            assert key in s, (what, "missing substation key " + key)
    assert j["model"] == "network" and j["curtailment"]["unsolved_instants"] == 0, what
def bounded(j, what):
    # The bound is on substation + curtailed traction energy of every timetable.
    b = j["bound_substation_kJ"]
    assert 0 < b <= j["substation_energy_kJ"] + j["curtailed_traction_kJ"] + 1e-6, (what, b)
    gap = (j["substation_energy_kJ"] + j["curtailed_traction_kJ"] - b) / j["substation_energy_kJ"]
    assert abs(gap - j["gap_fraction_of_substation"]) < 1e-9, what

ref = json.load(open("ref.json"))
network_keys(ref, "reference")
bounded(ref, "reference")
assert ref["trains"] == 100 and ref["time_step_s"] == 0.1
assert ref["bound_substation_kJ"] > 0.8 * ref["substation_energy_kJ"], ref["bound_substation_kJ"]

p = json.load(open("pat.json"))
network_keys(p, "pattern")
bounded(p, "pattern")
ps = p["pattern_search"]
assert p["substation_energy_kJ"] <= ps["headways_only_substation_energy_kJ"] + 1e-6, ps
assert abs(p["pattern"]["trip_time_s"] - 480) < 0.05, p["pattern"]
assert all(30 - 1e-9 <= d <= 45 + 1e-9 for d in p["pattern"]["dwells_s"]), p["pattern"]
assert sum(p["headways_s"]) == 1000 and all(150 <= h <= 250 for h in p["headways_s"])

windows, peak, off = [(600, 1200), (2000, 2400)], (120, 150), (300, 660)
def check(t, what):
    assert t[0] == 0 and t[-1] == 3000 and len(t) == 16, (what, t)
    for a, b in zip(t, t[1:]):
        lo, hi = peak if any(a < w1 and b > w0 for w0, w1 in windows) else off
        assert lo <= b - a <= hi, (what, a, b)
u, o, r = (json.load(open(f)) for f in ["wuni.json", "wopt.json", "wre.json"])
for j, what in [(u, "uniform"), (o, "optimum"), (r, "re-evaluated")]:
    network_keys(j, what)
    check(j["departures_s"], what)
rows = [x for x in csv.DictReader(open("wopt.csv")) if x["station"] == "A6"]
check([round(float(x["departure_s"])) for x in rows], "wopt.csv")
bounded(o, "windowed optimum")
assert o["substation_energy_kJ"] <= u["substation_energy_kJ"] + 1e-6
assert r["departures_s"] == o["departures_s"]
assert abs(r["substation_energy_kJ"] - o["substation_energy_kJ"]) <= 1e-9 * o["substation_energy_kJ"]
PY

[ "$fail" -eq 0 ] && echo "power_network_search: ok"
exit "$fail"
