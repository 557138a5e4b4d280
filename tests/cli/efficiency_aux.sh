#!/usr/bin/env bash
# Auxiliary power and efficiency maps on the command line (docs/formats.md, "Train TOML"):
# auxiliary_energy_kJ is the constant power times the time on the line (running and dwells) and
# changes no optimum at a fixed time; a train whose traction efficiency is a map solves, and its
# traction input lies between the work divided by the map's best and worst efficiency; a
# TTOBench train's "auxiliary power" is honoured; TTOBench cannot state a map, so exporting
# such a train is refused, and so are the fleet commands; a bad map is exit 2 naming its field.
source "$(dirname "$0")/lib/common.sh" "$@"
source "$src/tests/cli/lib/ttobench_fixtures.sh"

awk '/^\[davis\]/ && !done { print "auxiliary_power_kW = 150.0\n"; done = 1 } { print }' \
  "$src/data/contest/train.toml" > aux.toml
cp aux.toml map.toml
cat >> map.toml <<'TOML'

[traction_efficiency_map]
speeds_kmh = [0.0, 80.0]
forces_kN = [0.0, 250.0]
efficiency = [[0.95, 0.95], [0.6, 0.6]]
TOML

"$ecorail" solve --from A6 --to A7 --time 110 --quiet --json plain.json > /dev/null || fail=1
"$ecorail" solve --from A6 --to A7 --time 110 --quiet --train aux.toml --json aux.json \
  > /dev/null || { echo "FAIL: solve with auxiliary power"; fail=1; }
"$ecorail" solve --from A6 --to A8 --time 220 --dwell A7=45 --quiet --train aux.toml \
  --json journey.json > /dev/null || { echo "FAIL: journey with auxiliary power"; fail=1; }
"$ecorail" solve --from A6 --to A7 --time 110 --quiet --train map.toml --json map.json \
  > /dev/null || { echo "FAIL: solve with an efficiency map"; fail=1; }
python3 - <<'PY' || fail=1
import json
p, a, j, m = (json.load(open(f)) for f in ("plain.json", "aux.json", "journey.json", "map.json"))
assert p["auxiliary_energy_kJ"] == 0.0, p["auxiliary_energy_kJ"]
assert abs(a["auxiliary_energy_kJ"] - 150 * a["running_time_s"]) < 1e-6, a["auxiliary_energy_kJ"]
# The same optimum: auxiliary power adds the same energy to every run of 110 s.
assert a["traction_energy_kJ"] == p["traction_energy_kJ"], (a["traction_energy_kJ"], p["traction_energy_kJ"])
assert abs(j["trip_time_s"] - (220 + 45)) < 0.01, j["trip_time_s"]
assert abs(j["auxiliary_energy_kJ"] - 150 * j["trip_time_s"]) < 1e-6, j["auxiliary_energy_kJ"]
assert m["converged"] and abs(m["running_time_s"] - 110) <= 0.001
w, e = m["traction_energy_kJ"], m["traction_input_energy_kJ"]
assert w / 0.95 < e < w / 0.6, (w, e)
PY

# TTOBench: a train's auxiliary power is read.
flat_track track.data flat_2km "[0, 2000]" 60
hand_train train.data ', "auxiliary power": {"unit": "kW", "value": 80}'
"$ecorail" min-time --line track.data --train train.data --from S0 --to S1 --json t.json \
  > /dev/null || { echo "FAIL: TTOBench train with auxiliary power"; fail=1; }
python3 -c "
import json; t = json.load(open('t.json'))
assert abs(t['auxiliary_energy_kJ'] - 80 * t['running_time_s']) < 1e-6, t" || fail=1

# A train TTOBench could state but for its map (constant force under a power cap).
cat > capped.toml <<'TOML'
name = "capped"
mass_t = 200.0
rotating_mass_factor = 0.05
gravity_m_s2 = 9.81
max_speed_kmh = 100.0
traction_efficiency = 0.9
regen_efficiency = 0.8
[davis]
A = 1.0
B = 0.01
C = 0.0002
[traction]
points = [[0.0, 200.0]]
power_cap_kW = 2000.0
[braking]
points = [[0.0, 150.0]]
power_cap_kW = 2000.0
[traction_efficiency_map]
speeds_kmh = [0.0, 100.0]
forces_kN = [0.0, 200.0]
efficiency = [[0.9, 0.9], [0.8, 0.8]]
TOML
expect_error "are maps over speed and force" export --train capped.toml --ttobench-train out.json
sed 's/\[\[0.95, 0.95\], \[0.6, 0.6\]\]/[[0.95, 0.95], [0.6, 1.6]]/' map.toml > bad.toml
expect_error "traction_efficiency_map.efficiency[2][2]" solve --from A6 --to A7 --time 110 \
  --train bad.toml --json bad.json
# The fleet models use one regeneration efficiency: a train with maps is refused there.
expect_error "whose efficiencies are maps" timetable evaluate --uniform --train map.toml \
  --json fleet.json
expect_error "field '--train-file'" delay --reference --train 3 --station A9 --delay 10 \
  --train-file map.toml --json delay.json
exit $fail
