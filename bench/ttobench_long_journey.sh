#!/usr/bin/env bash
# A 48.5 km journey with three timing points between its stops (docs/ttobench.md, "A long
# journey with timing points"): TTOBench's 00_var_gradient_minusplus_6 with the VIRM6, past
# 12 km by 389 s, 24 km at exactly 735 s, 36 km in 1060-1100 s at 100-120 km/h, at rest at
# exactly 1560 s; least traction energy at the default grid. Prints the re-simulated traction
# energy, whether every window is met, the termination, the price evaluations and the wall and
# user time (/usr/bin/time). Usage:
#
#   bash bench/ttobench_long_journey.sh [ECORAIL] [extra solve flags, e.g. --ds 10 --dv 0.5]
#
# ECORAIL defaults to build/ecorail; TTOBench is read from ../shared/data/ttobench beside the
# source tree, or TTOBENCH=DIR.
set -euo pipefail

bin=${1:-build/ecorail}
shift || true
# shellcheck source=bench/ttobench_common.sh
. "$(dirname "$0")/ttobench_common.sh"

/usr/bin/time -f '%e %U' -o "$out_dir/time" "$bin" solve \
  --line "$ttobench/tracks/00_var_gradient_minusplus_6.json" \
  --train "$ttobench/trains/NL_Intercity_VIRM6.json" \
  --journey "$here/data/ttobench/00_var_gradient_minusplus_6_three_points_journey.json" \
  --quiet --json "$out_dir/run.json" "$@" >/dev/null
read -r wall user <"$out_dir/time"
python3 - "$out_dir/run.json" "$wall" "$user" <<'PY'
import json, sys
run = json.load(open(sys.argv[1]))
print("traction_energy_kJ %.1f" % run["traction_energy_kJ"])
print("windows_met %s" % str(run["windows_met"]).lower())
print("termination %s" % run["termination"])
print("price_evaluations %d" % run["search"]["lambda_evaluations"])
print("wall_s %s" % sys.argv[2])
print("user_s %s" % sys.argv[3])
PY
