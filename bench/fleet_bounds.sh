#!/usr/bin/env bash
# Question 2.1's power-flow optimum with its certificates: runs `timetable optimise` on the
# reference case with the window bound (timetable/window_bound.hpp) and prints the used
# regenerated energy, the bound on it, the gap in % of substation energy, the termination, the
# moves and the wall time from the JSON. Usage:
#
#   bash bench/fleet_bounds.sh [ECORAIL] [MOVES]
#
# ECORAIL defaults to build/ecorail, MOVES (annealing moves per run) to the program's default.
# Wall times depend on the machine's load: compare the search's own counts (moves) and the
# energies, not the seconds, across machines.
set -euo pipefail

bin=${1:-build/ecorail}
moves=${2:-}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
args=(timetable optimise --model power-flow --seed 1 --window-bound --quiet --json "$out/opt.json")
[ -n "$moves" ] && args+=(--moves "$moves")
/usr/bin/time -f "%e s wall, %U s user" "$bin" "${args[@]}" > "$out/log" 2> "$out/time"
python3 - "$out/opt.json" "$(tail -1 "$out/time")" <<'PY'
import json, sys
j = json.load(open(sys.argv[1]))
s = j["summary"]
print("| used regen kJ | used fraction | bound on used kJ | gap % of substation | termination | moves | time |")
print("|---|---|---|---|---|---|---|")
print(f"| {j['used_regen_kJ']:.1f} | {j['used_fraction_of_regen']:.4f} | {j['bound_used_regen_kJ']:.1f} | "
      f"{100 * j['gap_fraction_of_substation']:.3f} | {s['termination']} | {s['moves']} | {sys.argv[2]} |")
PY
