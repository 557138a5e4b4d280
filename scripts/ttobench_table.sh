#!/usr/bin/env bash
# Runs every TTOBench track with its matching train at the minimum running time +10 % and +30 %
# and prints a Markdown table: distance, minimum time, traction energy, solve wall time.
# A track with several stops runs as one journey S0 -> S_last stopping at every stop, its
# running time split optimally (one time price); its minimum time is the sum of the sections'.
#
#   scripts/ttobench_table.sh build/ecorail [TTOBENCH_DIR] [extra solver flags...]
#   scripts/ttobench_table.sh build/ecorail ../shared/data/ttobench --ds 10 --dv 0.5
#
# Track -> train (TTOBench pairs none; the choice is ours, docs/ttobench.md): the 00_* variants
# of the Dutch reference line run the NL VIRM6 intercity, the tunnel variant the FLIRT (the
# only train with tunnel drag data), St. Gallen-Wil and Stadelhofen-Altstetten the SBB KISS,
# Fribourg-Bern and Vasteras-Kolback the FLIRT, the Beijing line the Beijing subway train.
set -euo pipefail
bin=${1:?usage: ttobench_table.sh ECORAIL [TTOBENCH_DIR] [flags...]}
dir=${2:-$(dirname "$0")/../../shared/data/ttobench}
shift $(( $# >= 2 ? 2 : 1 ))
flags=("$@")
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

train_for() {
  case "$1" in
    00_reference_with_tunnels) echo CH_Stadler_FLIRT_TPF ;;
    00_*) echo NL_Intercity_VIRM6 ;;
    CH_StGallen_Wil | CH_Stadelhofen_Altstetten) echo CH_Stadler_KISS_SBB ;;
    CH_Fribourg_Bern | SE_Vasteras_Kolback) echo CH_Stadler_FLIRT_TPF ;;
    CN_*) echo CN_Beijing_Subway ;;
    *) echo "" ;;
  esac
}

stops_of() {
  python3 -c 'import json,sys; print(len(json.load(open(sys.argv[1]))["stops"]["values"]))' "$1"
}

echo "| track | train | stops | distance m | min time s | +10 %: energy kJ | solve s | +30 %: energy kJ | solve s |"
echo "|---|---|---|---|---|---|---|---|---|"
for track in "$dir"/tracks/*.json; do
  id=$(basename "$track" .json)
  train=$(train_for "$id")
  [ -n "$train" ] || { echo "| $id | (no train) | | | | | | | |"; continue; }
  n=$(stops_of "$track")
  last=$((n - 1))
  common=(--line "$track" --train "$dir/trains/$train.json" "${flags[@]}")
  tmin=0
  for ((i = 0; i < last; i++)); do
    "$bin" min-time "${common[@]}" --from "S$i" --to "S$((i + 1))" --json "$tmp/min_$i.json" \
      >/dev/null 2>&1
  done
  tmin=$(python3 -c 'import json,sys; print(sum(json.load(open(f))["min_running_time_s"] for f in sys.argv[1:]))' "$tmp"/min_*.json)
  row="| $id | $train | $n |"
  dist=""
  for pct in 10 30; do
    t=$(python3 -c "print(round($tmin * (1 + $pct / 100), 3))")
    start=$(date +%s.%N)
    if "$bin" solve "${common[@]}" --from S0 --to "S$last" --time "$t" --dwell 0 \
      --json "$tmp/run_$pct.json" >/dev/null 2>"$tmp/err_$pct.txt"; then
      wall=$(python3 -c "import time; print(f'{time.time() - $start:.1f}')")
      read -r d e < <(python3 - "$tmp/run_$pct.json" <<'PY'
import json, sys
j = json.load(open(sys.argv[1]))
d = j.get("distance_m") or sum(s["distance_m"] for s in j["sections"])
print(f'{d:.1f} {j["traction_energy_kJ"]:.1f}')
PY
)
      dist=$d
      row="$row@ $e | $wall |"
    else
      row="$row@ failed: $(head -c 120 "$tmp/err_$pct.txt") | |"
    fi
  done
  row=${row/@/ $dist | $(printf '%.3f' "$tmin") |}
  echo "${row//@/}"
  rm -f "$tmp"/min_*.json
done
