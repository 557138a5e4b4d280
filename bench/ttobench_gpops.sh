#!/usr/bin/env bash
# The GPOPS-II comparison of the ms-eetc repository (docs/ttobench.md, "The GPOPS-II case"):
# TTOBench's 00_var_speed_limit_100 with the VIRM6 as set up there, from 1 m/s to 1 m/s in
# exactly 1541 s, least net electrical energy. Prints the re-simulated net energy, its gap to
# GPOPS-II's published 440.1406 kWh (1 584 506.2 kJ), whether every window is met, the price
# evaluations, and the wall and user time (/usr/bin/time); with CALLGRIND=1 also the program's
# instruction count (valgrind --tool=callgrind, one thread; long: about 50 times the user time).
# Usage:
#
#   bash bench/ttobench_gpops.sh [ECORAIL] [extra solve flags, e.g. --ds 10 --dv 0.5]
#
# ECORAIL defaults to build/ecorail; TTOBench is read from ../shared/data/ttobench beside the
# source tree, or TTOBENCH=DIR.
set -euo pipefail

bin=${1:-build/ecorail}
shift || true
# shellcheck source=bench/ttobench_common.sh
. "$(dirname "$0")/ttobench_common.sh"

cmd=("$bin" solve --line "$ttobench/tracks/00_var_speed_limit_100.json"
  --train "$here/data/ttobench/NL_Intercity_VIRM6_gpops.json"
  --journey "$here/data/ttobench/00_var_speed_limit_100_gpops_journey.json"
  --objective net --quiet "$@")

/usr/bin/time -f '%e %U' -o "$out_dir/time" "${cmd[@]}" --json "$out_dir/run.json" >/dev/null
read -r wall user <"$out_dir/time"
python3 - "$out_dir/run.json" "$wall" "$user" <<'EOF'
import json, sys
run = json.load(open(sys.argv[1]))
gpops_kJ = 440.1406 * 3600.0
net = run["net_energy_kJ"]
print("net_energy_kJ %.1f" % net)
print("gap_to_gpops_ii %+.4f %%" % ((net / gpops_kJ - 1.0) * 100.0))
print("windows_met %s" % str(run["windows_met"]).lower())
print("termination %s" % run["termination"])
print("price_evaluations %d" % run["search"]["lambda_evaluations"])
print("wall_s %s" % sys.argv[2])
print("user_s %s" % sys.argv[3])
EOF

if [ "${CALLGRIND:-0}" != 0 ]; then
  OMP_NUM_THREADS=1 valgrind --tool=callgrind --callgrind-out-file="$out_dir/run.cg" \
    "${cmd[@]}" --threads 1 >/dev/null 2>"$out_dir/cg.log"
  echo "instructions $(sed -n 's/^summary: *//p; s/^totals: *//p' "$out_dir/run.cg" | head -1)"
fi
