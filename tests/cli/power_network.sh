#!/usr/bin/env bash
# `ecorail timetable --model network`: every bad field of a power-supply file is one clear error
# (exit 2, nothing written); a whole day of the reference case (100 trains, 0.1 s) closes its
# energy balance at every instant and over the day to 1e-9 and writes the keys, the substation
# power plot and the voltage plot; optimise under the network model on a small fleet is no
# worse than its uniform start.
set -uo pipefail
source "$(dirname "$0")/lib/common.sh" "$@"

supply="$src/data/contest/power_supply.toml"
small=(--from A6 --to A9 --trains 6 --span 1000 --headway 150:250 --trip-time 480)
outs=(--json out.json --power-plot p.svg --voltage-plot v.svg)

# One bad field at a time: (sed expression on the example, text the error must contain).
bad_cases=(
  's/^max_voltage_V = 900.0/max_voltage_V = 400.0/|trains.max_voltage_V'
  's/^min_voltage_V = 500.0/min_voltage_V = 0.0/|trains.min_voltage_V'
  's/^auxiliary_power_kW = 150.0/auxiliary_power_kW = -1.0/|trains.auxiliary_power_kW'
  's/^auxiliary_power_kW = 150.0/auxiliary_kW = 150.0/|trains.auxiliary_kW'
  's/^position_m = 4706.0/position_m = -4706.0/|substations[2].position_m'
  's/^position_m = 9309.0/position_m = 4000.0/|substations[3].position_m'
  '0,/^no_load_voltage_V = 835.0/s//no_load_voltage_V = 1000.0/|substations[1].no_load_voltage_V'
  '0,/^internal_resistance_ohm = 0.015/s//internal_resistance_ohm = 0.0/|substations[1].internal_resistance_ohm'
  '0,/^internal_resistance_ohm = 0.015/s//internal_resistance_ohm = 0.015\nreversible = "yes"/|substations[1].reversible'
  's/^name = "SS2 A4"/name = "SS1 A1"/|substations[2].name'
  's/^from_m = 0.0/from_m = 5.0/|conductors[1].from_m'
  's/^conductor_ohm_per_km = 0.008/conductor_ohm_per_km = -0.008/|conductors[1].conductor_ohm_per_km'
  's/^return_ohm_per_km = 0.015/return_ohm_per_km = "low"/|conductors[1].return_ohm_per_km'
  's/^\[trains\]/[trainz]/|trainz'
  's/^max_voltage_V = 900.0/max_voltage_V = [/|valid TOML'
)
for c in "${bad_cases[@]}"; do
  expr="${c%%|*}"
  needle="${c#*|}"
  sed "$expr" "$supply" > bad.toml
  expect_error "$needle" timetable evaluate "${small[@]}" --model network --power-supply bad.toml "${outs[@]}"
done
expect_error "--power-supply" timetable evaluate "${small[@]}" --model network "${outs[@]}"
expect_error "--power-supply" timetable evaluate "${small[@]}" --power-supply "$supply" --json out.json
expect_error "missing.toml" timetable evaluate "${small[@]}" --model network --power-supply missing.toml "${outs[@]}"
expect_error "--voltage-plot" timetable evaluate "${small[@]}" --voltage-plot v.svg
expect_error "--per-train-patterns" timetable optimise "${small[@]}" --model network --power-supply "$supply" --per-train-patterns --json o.json

# A whole day of the reference case.
"$ecorail" timetable evaluate --model network --power-supply "$supply" "${outs[@]}" \
  --voltage-at 3600 --window 3000:4200 > day.txt || { echo "FAIL: network day"; fail=1; }
for f in out.json p.svg v.svg; do
  [ -s "$f" ] || { echo "FAIL: $f not written"; fail=1; }
done
python3 - <<'PY' || fail=1
import json
j = json.load(open("out.json"))
for key in ["substations", "line_losses_kJ", "traction_input_kJ", "auxiliary_kJ", "used_regen_kJ",
            "curtailed_regen_kJ", "min_train_voltage_V", "max_train_voltage_V",
            "substation_energy_kJ", "regen_saving_kJ", "curtailment"]:
    assert key in j, "missing key " + key
for s in j["substations"]:
    for key in ["name", "position_m", "energy_kJ", "peak_power_kW", "peak_current_A"]:
        assert key in s, "missing substation key " + key
assert j["model"] == "network" and j["time_step_s"] == 0.1 and j["trains"] == 100
assert j["curtailment"]["instants"] > 640000, j["curtailment"]
assert j["curtailment"]["unsolved_instants"] == 0, j["curtailment"]
# Conservation at every instant and over the day.
assert j["max_balance_error_fraction"] < 1e-9, j["max_balance_error_fraction"]
lhs = j["substation_energy_kJ"] + j["used_regen_kJ"]
rhs = j["traction_input_kJ"] + j["auxiliary_kJ"] + j["line_losses_kJ"]
assert abs(lhs - rhs) <= 1e-9 * rhs, (lhs, rhs)
assert abs(sum(s["energy_kJ"] for s in j["substations"]) - j["substation_energy_kJ"]) <= 1e-6 * rhs
# The reference train's traction efficiency is 1: traction input = traction at the wheel less
# what was curtailed; auxiliaries are 150 kW for every train's 2086 s (the re-simulated trip
# arrives within a few ms of it).
assert abs(j["traction_input_kJ"] + j["curtailed_traction_kJ"] - j["traction_energy_kJ"]) < 1e-6 * rhs
assert abs(j["auxiliary_kJ"] - 100 * 150 * 2086) < 1e-6 * 100 * 150 * 2086, j["auxiliary_kJ"]
assert 500 <= j["min_train_voltage_V"] <= j["max_train_voltage_V"] <= 900 + 1e-9
assert j["regen_saving_kJ"] > 0
PY

# Optimise on the network: never worse than the uniform timetable it starts from.
"$ecorail" timetable evaluate "${small[@]}" --model network --power-supply "$supply" --json u.json > /dev/null ||
  { echo "FAIL: small evaluate"; fail=1; }
"$ecorail" timetable optimise "${small[@]}" --model network --power-supply "$supply" --moves 300 --quiet \
  --json o.json > o.txt || { echo "FAIL: small optimise"; cat o.txt; fail=1; }
python3 - <<'PY' || fail=1
import json
u, o = json.load(open("u.json")), json.load(open("o.json"))
assert o["model"] == "network"
assert o["substation_energy_kJ"] <= u["substation_energy_kJ"] + 1e-6, (o["substation_energy_kJ"], u["substation_energy_kJ"])
assert sum(o["headways_s"]) == 1000 and all(150 <= h <= 250 for h in o["headways_s"])
# The solver's summary line names the regenerated energy the line took, as the JSON does (not
# traction minus substation energy, which auxiliaries and losses make negative).
import re
line = [l for l in open("o.txt") if "annealing" in l and "used regen" in l]
assert line, open("o.txt").read()
used = float(re.search(r"used regen (-?[0-9.]+) kJ", line[0]).group(1))
assert abs(used - o["used_regen_kJ"]) <= 0.05 + 1e-9, (used, o["used_regen_kJ"])
PY

[ "$fail" -eq 0 ] && echo "power_network: ok"
exit "$fail"
