#!/usr/bin/env bash
# `solve` and `frontier` answer one question alike: a frontier point is the stand-alone solve of
# its running time (the same search path, dp/frontier.hpp), so for several sections and times
# both print the same traction energy to the printed digit (0.1 kJ) and the same running time.
source "$(dirname "$0")/lib/common.sh" "$@"

for case in "A6 A7 145 160" "A3 A4 150 160" "A12 A13 110 120"; do
  set -- $case
  from=$1 to=$2 t0=$3 t1=$4
  if ! "$ecorail" frontier --from "$from" --to "$to" --tmin "$t0" --tmax "$t1" --step 5 \
      --no-cache --quiet --csv f.csv > /dev/null; then
    echo "FAIL: frontier $from -> $to"; fail=1; continue
  fi
  for t in $(seq "$t0" 5 "$t1"); do
    line=$("$ecorail" solve --from "$from" --to "$to" --time "$t" --quiet | head -1)
    solve_kJ=$(echo "$line" | sed -n 's/.*: traction \([0-9.]*\) kJ.*/\1/p')
    solve_s=$(echo "$line" | sed -n 's/.* in \([0-9.]*\) s:.*/\1/p')
    front_kJ=$(awk -F, -v t="$t" 'NR > 1 && $3 + 0 == t {printf "%.1f", $5}' f.csv)
    front_s=$(awk -F, -v t="$t" 'NR > 1 && $3 + 0 == t {printf "%.3f", $4}' f.csv)
    if [ -z "$solve_kJ" ] || [ "$solve_kJ" != "$front_kJ" ] || [ "$solve_s" != "$front_s" ]; then
      echo "FAIL: $from -> $to at $t s: solve $solve_kJ kJ in $solve_s s, frontier $front_kJ kJ in $front_s s"
      fail=1
    fi
  done
done
exit $fail
