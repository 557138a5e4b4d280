#!/usr/bin/env bash
# Two threads against one on a busy machine: runs the A6 -> A7 solve and the whole
# line with --threads 1 and --threads 2, first with nothing else running, then while a
# competing busy process (a shell loop) occupies one core, and prints the median wall time of
# each (the runs of the four variants alternate, so a change in the machine's load falls on
# all of them alike). Usage:
#
#   bash bench/threads_under_load.sh [ECORAIL] [RUNS]
#
# ECORAIL defaults to build/ecorail, RUNS (per variant and case) to 7.
set -euo pipefail

bin=${1:-build/ecorail}
runs=${2:-7}
out=$(mktemp -d)
busy_pid=""
stop_busy() {
  if [ -n "$busy_pid" ]; then
    kill "$busy_pid" 2>/dev/null || true
    wait "$busy_pid" 2>/dev/null || true
    busy_pid=""
  fi
}
trap 'stop_busy; rm -rf "$out"' EXIT

declare -A cmd=(
  [section]="$bin solve --from A6 --to A7 --time 110 --quiet"
  [line]="$bin solve --from A1 --to A14 --time 1726 --dwell 30 --quiet"
)

# seconds of one run of CASE with THREADS
one_run() {
  # shellcheck disable=SC2086
  /usr/bin/time -f '%e' -o "$out/t" ${cmd[$1]} --threads "$2" > /dev/null 2>&1
  tail -1 "$out/t"
}

for load in idle busy; do
  if [ "$load" = busy ]; then
    bash -c 'while :; do :; done' &
    busy_pid=$!
  fi
  for c in section line; do
    for ((r = 0; r < runs; r++)); do
      for t in 1 2; do one_run "$c" "$t" >> "$out/$load.$c.$t"; done
    done
  done
  stop_busy
done

median() { sort -g "$1" | awk '{a[NR] = $1} END {print (NR % 2) ? a[(NR + 1) / 2] : (a[NR / 2] + a[NR / 2 + 1]) / 2}'; }
printf '%-8s %-6s %12s %12s %10s\n' case load "1 thread s" "2 threads s" "2 / 1"
for c in section line; do
  for load in idle busy; do
    m1=$(median "$out/$load.$c.1")
    m2=$(median "$out/$load.$c.2")
    printf '%-8s %-6s %12.3f %12.3f %10.3f\n' "$c" "$load" "$m1" "$m2" \
      "$(awk -v a="$m2" -v b="$m1" 'BEGIN {print a / b}')"
  done
done
echo "load average at the end: $(cut -d' ' -f1-3 /proc/loadavg); $(nproc) cores"
