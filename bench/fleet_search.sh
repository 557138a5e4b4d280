#!/usr/bin/env bash
# The fleet headway search on questions 2.1 and 2.2 (power-flow model, 0.01 s): used fraction of
# the regenerated energy, substation energy, proven gap (whatever the model's current bound
# gives) and the CPU and wall time of each run, from the program's JSON (every figure is the
# forward re-simulation of the timetable found). Long: each 2.2 run takes its whole limit.
#
#   bash bench/fleet_search.sh [ECORAIL] [CASE...]
#
# ECORAIL defaults to build/ecorail. CASE is any of: 2.1 (defaults, seed 1), 2.1-60 (the same
# with --time-limit 60), 2.2-300, 2.2-600 (the 240-train peak day with --time-limit 300 or 600;
# the longer run continues the shorter one's rounds, so it is never worse when both finish the
# first round), 120-60, 200-60 (120 or 200 trains, one headway class, --time-limit 60: the
# periodic-regime start with one class), net-60 (the network model's reference day with the
# example supply, --time-limit 60), net2.2-120 (its 2.2 day, --time-limit 120). Default: 2.1
# 2.2-300. THREADS sets --threads (default: OpenMP's).
set -euo pipefail

bin=${1:-build/ecorail}
shift || true
cases=("$@")
[ ${#cases[@]} -gt 0 ] || cases=(2.1 2.2-300)
threads=()
[ -n "${THREADS:-}" ] && threads=(--threads "$THREADS")
out_dir=$(mktemp -d)
trap 'rm -rf "$out_dir"' EXIT
day=(--trains 240 --peak 7200:12600 --peak 43200:50400 --peak-headway 120:150
  --offpeak-headway 300:660)
net=(--model network --power-supply data/contest/power_supply.toml)

args_of() {
  case "$1" in
    2.1) echo "--model power-flow --seed 1" ;;
    2.1-60) echo "--model power-flow --seed 1 --time-limit 60" ;;
    2.2-300) echo "${day[*]} --seed 1 --time-limit 300" ;;
    2.2-600) echo "${day[*]} --seed 1 --time-limit 600" ;;
    120-60) echo "--trains 120 --seed 1 --time-limit 60" ;;
    200-60) echo "--trains 200 --seed 1 --time-limit 60" ;;
    net-60) echo "${net[*]} --seed 1 --time-limit 60" ;;
    net2.2-120) echo "${net[*]} ${day[*]} --seed 1 --time-limit 120" ;;
    *)
      echo "unknown case '$1' (2.1, 2.1-60, 2.2-300, 2.2-600, 120-60, 200-60, net-60," \
        "net2.2-120)" >&2
      exit 2
      ;;
  esac
}

printf '| case | command | used fraction | substation kJ | gap (of substation) | CPU s | wall s |\n'
printf '|---|---|---|---|---|---|---|\n'
for c in "${cases[@]}"; do
  read -r -a a <<<"$(args_of "$c")"
  json="$out_dir/$c.json"
  /usr/bin/time -f '%U %e' -o "$out_dir/time" \
    "$bin" timetable optimise "${a[@]}" "${threads[@]}" --quiet --json "$json" >/dev/null
  read -r cpu wall <"$out_dir/time"
  python3 - "$json" "$c" "${a[*]}" "$cpu" "$wall" <<'EOF'
import json, sys
j = json.load(open(sys.argv[1]))
gap = j.get("gap_fraction_of_substation")
gap_text = "none" if gap is None else "%.4f %%" % (100 * gap)
print("| %s | `ecorail timetable optimise %s` | %.4f | %.1f | %s | %s | %s |" % (
    sys.argv[2], sys.argv[3], j["used_fraction_of_regen"], j["substation_energy_kJ"], gap_text,
    sys.argv[4], sys.argv[5]))
EOF
done
