#!/usr/bin/env bash
# The reference line in two forms: the contest data compiled into ecorail (A1..A14) and
# TTOBench's CN_Songjiazhuang_Yizhuang (S0..S13, S0 = A14). Prints, per section, the minimum
# running time with (1) the contest line and train, (2) the TTOBench track and the contest
# train (only the track differs), (3) the TTOBench track and train (CN_Beijing_Subway); then
# the A1 -> A14 journey in 1726 s of running time with 30 s dwells in each form.
#
#   scripts/ttobench_reference.sh build/ecorail [TTOBENCH_DIR]
set -euo pipefail
bin=${1:?usage: ttobench_reference.sh ECORAIL [TTOBENCH_DIR]}
dir=${2:-$(dirname "$0")/../../shared/data/ttobench}
track="$dir/tracks/CN_Songjiazhuang_Yizhuang.json"
beijing="$dir/trains/CN_Beijing_Subway.json"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
mt() {
  "$bin" min-time "$@" --json "$tmp/m.json" > /dev/null 2>&1 &&
    python3 -c 'import json, sys; print("%.2f" % json.load(open(sys.argv[1]))["min_running_time_s"])' "$tmp/m.json"
}

echo "| section | contest line + train: min s | TTOBench track + contest train | TTOBench track + Beijing train |"
echo "|---|---|---|---|"
for i in $(seq 1 13); do
  a="A$i"; b="A$((i + 1))"; s="S$((14 - i))"; t="S$((13 - i))"
  echo "| $a -> $b ($s -> $t) | $(mt --from "$a" --to "$b") | $(mt --line "$track" --from "$s" --to "$t") | $(mt --line "$track" --train "$beijing" --from "$s" --to "$t") |"
done
echo
echo "| A1 -> A14, 1726 s running, 30 s dwells | traction kJ | regenerated kJ | solve s |"
echo "|---|---|---|---|"
run() {
  local label="$1"; shift
  local start; start=$(date +%s.%N)
  if "$bin" solve "$@" --time 1726 --dwell 30 --quiet --json "$tmp/j.json" > /dev/null 2> "$tmp/err"; then
    python3 - "$tmp/j.json" "$label" "$start" <<'PY'
import json, sys, time
j = json.load(open(sys.argv[1]))
print(f"| {sys.argv[2]} | {j['traction_energy_kJ']:.1f} | {j['regen_energy_kJ']:.1f} | {time.time() - float(sys.argv[3]):.1f} |")
PY
  else
    echo "| $label | failed: $(head -c 150 "$tmp/err") | | |"
  fi
}
run "contest line + train" --from A1 --to A14
run "TTOBench track + contest train" --line "$track" --from S13 --to S0
run "TTOBench track + Beijing train" --line "$track" --train "$beijing" --from S13 --to S0
