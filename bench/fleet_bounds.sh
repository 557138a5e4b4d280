#!/usr/bin/env bash
# Question 2.1's power-flow optimum with its certificate: runs `timetable optimise` on the
# reference case with its defaults (the power-flow model certifies with the window bound,
# energy/window_bound.hpp) and prints the used regenerated energy, the bound on it, the gap in %
# of the substation energy, the termination, the method, the moves and the time from the JSON.
# Usage:
#
#   bash bench/fleet_bounds.sh [ECORAIL] [EXTRA FLAGS...]
#
# ECORAIL defaults to build/ecorail; extra flags go to `timetable optimise` (e.g. --moves N).
# Wall times depend on the machine's load: compare the energies, the moves and the user CPU
# time across machines, not the wall seconds.
set -euo pipefail

bin=${1:-build/ecorail}
shift || true
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
/usr/bin/time -f "%e s wall, %U s user" "$bin" timetable optimise --model power-flow --seed 1 \
  --quiet --json "$out/opt.json" "$@" > "$out/log" 2> "$out/time"
python3 - "$out/opt.json" "$(tail -1 "$out/time")" <<'PY'
import json, sys
j = json.load(open(sys.argv[1]))
s = j["summary"]
print("| substation kJ | used regen kJ | used fraction | bound on used kJ | gap % of substation | termination | method | moves | time |")
print("|---|---|---|---|---|---|---|---|---|")
print(f"| {j['substation_energy_kJ']:.1f} | {j['used_regen_kJ']:.1f} | {j['used_fraction_of_regen']:.4f} | "
      f"{j['bound_used_regen_kJ']:.1f} | {100 * j['gap_fraction_of_substation']:.3f} | "
      f"{s['termination']} | {s['method']} | {s['moves']} | {sys.argv[2]} |")
PY
