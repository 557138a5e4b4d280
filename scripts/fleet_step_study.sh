#!/usr/bin/env bash
# Time-step convergence of the power-flow model: evaluates one timetable at steps from 1 s down
# to 1 ms and prints used regenerated and substation energy with the difference to the finest.
# Usage: scripts/fleet_step_study.sh [ECORAIL] [timetable evaluate options...]
#   e.g. scripts/fleet_step_study.sh build/ecorail --headways data/contest/published_headways_2_1.csv
set -euo pipefail
ecorail=${1:-build/ecorail}
shift || true
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
steps=(1 0.5 0.2 0.1 0.05 0.02 0.01 0.005 0.002 0.001)
for step in "${steps[@]}"; do
  "$ecorail" timetable evaluate --model power-flow --step "$step" "$@" --json "$tmp/$step.json" > /dev/null
done
python3 - "$tmp" "${steps[@]}" <<'PY'
import json, sys
d, steps = sys.argv[1], sys.argv[2:]
rows = [(s, json.load(open(f"{d}/{s}.json"))) for s in steps]
fine = rows[-1][1]
print(f"{'step_s':>8} {'used_regen_kJ':>15} {'substation_kJ':>15} {'substation_vs_finest_%':>24}")
for s, j in rows:
    rel = 100.0 * (j["substation_energy_kJ"] - fine["substation_energy_kJ"]) / fine["substation_energy_kJ"]
    print(f"{s:>8} {j['used_regen_kJ']:15.1f} {j['substation_energy_kJ']:15.1f} {rel:24.5f}")
PY
