#!/usr/bin/env bash
# Instruction counts (valgrind's callgrind, one thread, independent of the machine's load) and
# wall times (hyperfine if installed, else /usr/bin/time; one thread) of the engine's reference
# jobs. Usage:
#
#   bash bench/instructions.sh [ECORAIL] [CASE...]
#
# ECORAIL defaults to build/ecorail. CASE is any of: section (A6 -> A7 in 110 s), line (A1 ->
# A14 in 1726 s with 30 s dwells), frontier (the frontier of A6 -> A7 at 1 s steps, 61 points,
# not cached), frontiers (all 13 frontiers at 1 s steps, not cached; long under callgrind),
# long (TTOBench's 48.5 km reference track in 1500 s, passing S1 and S2; long under callgrind;
# needs ../shared/data/ttobench beside the source tree, or TTOBENCH=DIR).
# Default: section line frontier. Set WALL=0 to skip the wall times, CALLGRIND=0 to skip the
# instruction counts, RUNS to change hyperfine's number of runs (default 5).
set -euo pipefail

bin=${1:-build/ecorail}
shift || true
cases=("$@")
[ ${#cases[@]} -gt 0 ] || cases=(section line frontier)
runs=${RUNS:-5}
ttobench=${TTOBENCH:-$(dirname "$0")/../../shared/data/ttobench}
out_dir=$(mktemp -d)
trap 'rm -rf "$out_dir"' EXIT

command_of() {
  case "$1" in
    section) echo "$bin solve --from A6 --to A7 --time 110 --threads 1 --quiet" ;;
    line) echo "$bin solve --from A1 --to A14 --time 1726 --dwell 30 --threads 1 --quiet" ;;
    frontier) echo "$bin frontier --from A6 --to A7 --step 1 --no-cache --threads 1 --quiet" ;;
    frontiers) echo "$bin frontier --all --step 1 --no-cache --threads 1 --quiet" ;;
    long)
      echo "$bin solve --line $ttobench/tracks/00_reference.json --train" \
        "$ttobench/trains/NL_Intercity_VIRM6.json --from S0 --to S3 --pass-through S1" \
        "--pass-through S2 --time 1500 --threads 1 --quiet"
      ;;
    *)
      echo "unknown case '$1' (section, line, frontier, frontiers, long)" >&2
      exit 2
      ;;
  esac
}

printf '%-10s %16s %12s  %s\n' case instructions wall_s command
for c in "${cases[@]}"; do
  cmd=$(command_of "$c")
  instr=-
  if [ "${CALLGRIND:-1}" != 0 ]; then
    # One thread: callgrind serialises threads anyway, and the count is the work of one core.
    # shellcheck disable=SC2086
    OMP_NUM_THREADS=1 valgrind --tool=callgrind --callgrind-out-file="$out_dir/$c.cg" \
      $cmd >/dev/null 2>"$out_dir/$c.log"
    instr=$(sed -n 's/^summary: *//p; s/^totals: *//p' "$out_dir/$c.cg" | head -1)
  fi
  wall=-
  if [ "${WALL:-1}" != 0 ]; then
    if command -v hyperfine >/dev/null; then
      OMP_NUM_THREADS=1 hyperfine -N -w 1 -r "$runs" --export-json "$out_dir/$c.json" "$cmd" \
        >/dev/null 2>&1
      wall=$(python3 -c 'import json,sys; print("%.3f" % json.load(open(sys.argv[1]))["results"][0]["median"])' \
        "$out_dir/$c.json")
    else
      # shellcheck disable=SC2086
      OMP_NUM_THREADS=1 /usr/bin/time -f '%e' -o "$out_dir/$c.time" $cmd >/dev/null 2>&1
      wall=$(tail -1 "$out_dir/$c.time")
    fi
  fi
  printf '%-10s %16s %12s  %s\n' "$c" "$instr" "$wall" "$cmd"
done
