#!/usr/bin/env bash
# Grid study: solves one section on a ladder of grids and prints the re-simulated energy of
# each against the finest. Usage: scripts/grid_study.sh [ecorail] [from] [to] [time]
set -euo pipefail
ecorail="${1:-build/ecorail}"
from="${2:-A6}"; to="${3:-A7}"; time="${4:-110}"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
grids=("20 1.0" "10 0.5" "10 0.2" "5 0.5" "5 0.2" "2.5 0.1" "2 0.1" "1 0.05")
printf "%-8s %-8s %10s %14s %12s %10s %9s\n" ds_m dv_kmh nodes traction_kJ running_s stop_m wall_s
for g in "${grids[@]}"; do
  set -- $g
  "$ecorail" solve --from "$from" --to "$to" --time "$time" --ds "$1" --dv "$2" \
    --json "$tmp/$1_$2.json" > /dev/null
done
python3 - "$tmp" "${grids[@]}" <<'PY'
import json, sys
tmp, grids = sys.argv[1], sys.argv[2:]
rows = [json.load(open(f"{tmp}/{g.split()[0]}_{g.split()[1]}.json")) for g in grids]
finest = rows[-1]["traction_energy_kJ"]
for g, j in zip(grids, rows):
    ds, dv = g.split()
    print(f"{ds:<8} {dv:<8} {j['grid']['nodes']:>10} {j['traction_energy_kJ']:>14.3f} "
          f"{j['running_time_s']:>12.4f} {j['stop_error_m']:>10.4f} {j['solve_wall_s']:>9.3f}"
          f"   {100 * (j['traction_energy_kJ'] - finest) / finest:+.4f} % vs finest")
PY
