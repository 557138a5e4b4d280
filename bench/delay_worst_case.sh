#!/usr/bin/env bash
# The worst single delay of issue 25 item 2: `ecorail delay --delay 600` with every held-up
# follower driven (--followers 1000: the cascade is followed until a train is not held up) for
# late trains in both peak windows of the 2.2 day, leaving late at several stations (the early
# ones give the longest cascades). Prints per case the train, the station, the followers held
# up, wall and user CPU seconds (/usr/bin/time), then the largest wall and user figures.
# Usage:
#
#   bash bench/delay_worst_case.sh [ECORAIL] [DAY.csv]
#
# ECORAIL defaults to build/ecorail, DAY.csv to ecorail-day.csv in the temporary directory (made
# first when absent, as bench/montecarlo_followers.sh makes it). TRAINS, STATIONS and DELAY
# (environment) replace the default cases: trains 28 40 52 150 170 190, stations A1 A2 A3 A9,
# delay 600 s. The frontiers come from the cache (the first run of a fresh cache makes them).
set -euo pipefail

bin=${1:-build/ecorail}
day=${2:-${TMPDIR:-/tmp}/ecorail-day.csv}
trains=${TRAINS:-28 40 52 150 170 190}
stations=${STATIONS:-A1 A2 A3 A9}
delay=${DELAY:-600}
# shellcheck source=bench/day_plan.sh
. "$(dirname "$0")/day_plan.sh"
ensure_day_plan "$bin" "$day"
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
# Warm the frontier cache so that no case pays for making it.
"$bin" delay --plan "$day" --train 1 --station A1 --delay 1 --followers 0 --quiet > /dev/null
printf '%-6s %-8s %-8s %8s %8s\n' train station held_up wall_s user_s
max_wall=0 max_user=0 worst=""
for t in $trains; do
  for s in $stations; do
    /usr/bin/time -f "%e %U" -o "$out/time" "$bin" delay --plan "$day" --train "$t" \
      --station "$s" --delay "$delay" --followers 1000 --quiet > "$out/report"
    read -r wall user < "$out/time"
    held=$(grep -c ': HELD UP' "$out/report" || true)
    printf '%-6s %-8s %-8s %8s %8s\n' "$t" "$s" "$held" "$wall" "$user"
    if awk -v a="$wall" -v b="$max_wall" 'BEGIN { exit !(a > b) }'; then
      max_wall=$wall
      worst="train $t at $s"
    fi
    if awk -v a="$user" -v b="$max_user" 'BEGIN { exit !(a > b) }'; then max_user=$user; fi
  done
done
echo "max: $max_wall s wall ($worst), $max_user s user"
