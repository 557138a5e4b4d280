#!/usr/bin/env bash
# Every TTOBench instance run by ecorail, as one Markdown table on stdout: each track with each
# train that can run it (at the track's minimum running time +10 % and +30 %), and each journey
# (TTOBench's own and the variants in data/ttobench/) with its train: traction and net energy,
# running time, whether every window (or the running time) is met, and the wall time of the
# `solve` command. A track with more than two stops runs as one journey S0 -> S_last stopping at
# every stop, its running time split optimally (one time price); its minimum time is the sum of
# the sections' flat-out times. A pair the program refuses (e.g. a tunnel track and a train
# without tunnel drag data) is a row saying so, as is a journey whose windows no run can meet.
#
#   scripts/ttobench_table.sh build/ecorail [TTOBENCH_DIR] [extra solver flags...]
#   scripts/ttobench_table.sh build/ecorail ../shared/data/ttobench --ds 10 --dv 0.5
#
# Environment: TRAINS="A B" limits the trains (file names without .json, default: all of
# TTOBENCH_DIR/trains), TRACKS="x y" the tracks, JOURNEYS=0 leaves the journeys out,
# JOURNEY_MATCH='glob' keeps the journeys whose id matches, TRACK_RUNS=0 leaves the track rows out,
# TIME_LIMIT=S stops a `solve` after S seconds of wall time (default 600): its row then says
# "stopped at the time limit" and carries no figures.
set -euo pipefail
bin=${1:?usage: ttobench_table.sh ECORAIL [TTOBENCH_DIR] [flags...]}
dir=${2:-$(dirname "$0")/../../shared/data/ttobench}
shift $(($# >= 2 ? 2 : 1))
flags=("$@")
repo=$(cd "$(dirname "$0")/.." && pwd)
limit=${TIME_LIMIT:-600}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

trains=${TRAINS:-$(for f in "$dir"/trains/*.json; do basename "$f" .json; done)}
tracks=${TRACKS:-$(for f in "$dir"/tracks/*.json; do basename "$f" .json; done)}

stops_of() {
  python3 -c 'import json,sys; print(len(json.load(open(sys.argv[1]))["stops"]["values"]))' "$1"
}
now() { date +%s.%N; }
since() { python3 -c "import sys; print(f'{float(sys.argv[2]) - float(sys.argv[1]):.1f}')" "$1" "$(now)"; }
# The first line of an error, shortened for a table cell (what was expected, pipes escaped).
why() {
  grep -m1 -E "error|ecorail:" "$1" | sed 's/^ecorail: //; s/.*expected //; s/|/\\|/g' | cut -c1-220
}
# traction kJ | net kJ | running time s | windows met, from a solve's JSON report.
figures() {
  python3 - "$1" <<'PY'
import json, sys
j = json.load(open(sys.argv[1]))
net = j.get("net_energy_kJ")
if net is None and j.get("sections"):
    net = sum(s["net_energy_kJ"] for s in j["sections"])
met = j.get("windows_met")
met = "-" if met is None else ("yes" if met else "NO")
print(f'{j["traction_energy_kJ"]:.1f} | {"-" if net is None else f"{net:.1f}"} | '
      f'{j["running_time_s"]:.3f} | {met}')
PY
}

echo "| track | train | run | traction kJ | net kJ | running time s | windows met | solve wall s |"
echo "|---|---|---|---|---|---|---|---|"

if [ "${TRACK_RUNS:-1}" != 0 ]; then
  for id in $tracks; do
    track="$dir/tracks/$id.json"
    n=$(stops_of "$track")
    last=$((n - 1))
    for train in $trains; do
      common=(--line "$track" --train "$dir/trains/$train.json" "${flags[@]}")
      ok=1
      rm -f "$tmp"/min_*.json
      for ((i = 0; i < last; i++)); do
        if ! "$bin" min-time "${common[@]}" --from "S$i" --to "S$((i + 1))" \
          --json "$tmp/min_$i.json" >/dev/null 2>"$tmp/err.txt"; then
          echo "| $id | $train | cannot run: $(why "$tmp/err.txt") | | | | | |"
          ok=0
          break
        fi
      done
      [ "$ok" = 1 ] || continue
      tmin=$(python3 -c 'import json,sys; print(sum(json.load(open(f))["min_running_time_s"] for f in sys.argv[1:]))' "$tmp"/min_*.json)
      for pct in 10 30; do
        t=$(python3 -c "print(round($tmin * (1 + $pct / 100), 3))")
        run="+$pct % ($t s)"
        start=$(now)
        rc=0
        timeout "$limit" "$bin" solve "${common[@]}" --from S0 --to "S$last" --time "$t" --dwell 0 \
          --quiet --json "$tmp/run.json" >/dev/null 2>"$tmp/err.txt" || rc=$?
        if [ "$rc" = 0 ]; then
          echo "| $id | $train | $run | $(figures "$tmp/run.json") | $(since "$start") |"
        elif [ "$rc" = 124 ]; then
          echo "| $id | $train | $run: stopped at the time limit ($limit s), no result | | | | | $(since "$start") |"
        else
          echo "| $id | $train | $run: failed ($(why "$tmp/err.txt")) | | | | | $(since "$start") |"
        fi
      done
    done
  done
fi

# The journey's train: the pairing of docs/ttobench.md, the GPOPS comparison's own train, and the
# VIRM6 for the long journey with timing points (bench/ttobench_long_journey.sh).
journey_train() {
  case "$1" in
    *gpops*) echo "$repo/data/ttobench/NL_Intercity_VIRM6_gpops.json" ;;
    CH_StGallen_Wil*) echo "$dir/trains/CH_Stadler_KISS_SBB.json" ;;
    00_var_gradient_minusplus_6_three_points*) echo "$dir/trains/NL_Intercity_VIRM6.json" ;;
    *) echo "" ;;
  esac
}

if [ "${JOURNEYS:-1}" != 0 ]; then
  for journey in "$dir"/journeys/*.json "$repo"/data/ttobench/*[Jj]ourney*.json; do
    [ -f "$journey" ] || continue
    jid=$(basename "$journey" .json)
    # shellcheck disable=SC2254
    case "$jid" in ${JOURNEY_MATCH:-*}) ;; *) continue ;; esac
    track_id=$(python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["metadata"]["associated track"])' "$journey")
    train=$(journey_train "$jid")
    [ -n "$train" ] || { echo "| $track_id | (no train) | journey $jid | | | | | |"; continue; }
    objective=()
    case "$jid" in *gpops*) objective=(--objective net) ;; esac
    start=$(now)
    rc=0
    timeout "$limit" "$bin" solve --line "$dir/tracks/$track_id.json" --train "$train" \
      --journey "$journey" "${objective[@]}" "${flags[@]}" --quiet --json "$tmp/run.json" \
      >/dev/null 2>"$tmp/err.txt" || rc=$?
    name="$track_id | $(basename "$train" .json) | journey $jid"
    if [ "$rc" = 0 ]; then
      echo "| $name | $(figures "$tmp/run.json") | $(since "$start") |"
    elif [ "$rc" = 124 ]; then
      echo "| $name: stopped at the time limit ($limit s), no result | | | | | $(since "$start") |"
    elif [ "$rc" = 2 ]; then
      echo "| $name: refused ($(why "$tmp/err.txt")) | | | | | $(since "$start") |"
    else
      echo "| $name: FAILED, exit $rc ($(why "$tmp/err.txt")) | | | | | $(since "$start") |"
    fi
  done
fi
