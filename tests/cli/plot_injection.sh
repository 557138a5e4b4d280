#!/usr/bin/env bash
# Nothing a user names runs as a command inside gnuplot: a plot path or a station
# name holding ';system('touch X');print(' (or a backquoted command) is drawn as text, for the
# speed plot of solve and the energy-time plot of frontier; the file X never appears.
set -uo pipefail
source "$(dirname "$0")/lib/common.sh" "$@"

command -v gnuplot > /dev/null || { echo "plot_injection: skipped (no gnuplot)"; exit 0; }

check_no_x() {  # check_no_x <what>
  if [ -e X ] || [ -e "$work/X" ]; then
    echo "FAIL: $1 ran a command"; fail=1; rm -f X "$work/X"
  fi
}

# A copy of the reference line whose station A7 is called $1.
line_with_a7_named() {
  rm -rf line
  mkdir line
  cp "$src"/data/contest/*.csv line/
  NAME="$1" python3 -c '
import os
path = "line/stations.csv"
text = open(path).read().replace("\nA7,", "\n" + os.environ["NAME"] + ",")
open(path, "w").write(text)'
}

# The path vector: the file name closes gnuplot's quote and calls system(). The command names
# X by its absolute path, so it would show wherever gnuplot runs; the directories are made.
for plot in "$work/a';system('touch $work/X');print('.svg" \
  "$work/a';system('touch X');print('.png"; do
  mkdir -p "$(dirname "$plot")"
  "$ecorail" solve --from A6 --to A7 --time 110 --plot "$plot" > /dev/null 2> err.txt ||
    { echo "FAIL: solve with a quoted plot path"; cat err.txt; fail=1; }
  [ -s "$plot" ] || { echo "FAIL: plot not written: $plot"; fail=1; }
  check_no_x "solve --plot $plot"
done
plot="$work/f';system('touch $work/X');print('.svg"
mkdir -p "$(dirname "$plot")"
"$ecorail" frontier --from A6 --to A7 --tmin 100 --tmax 120 --step 10 --plot "$plot" \
  > /dev/null 2> err.txt || { echo "FAIL: frontier with a quoted plot path"; cat err.txt; fail=1; }
[ -s "$plot" ] || { echo "FAIL: frontier plot not written"; fail=1; }
check_no_x "frontier --plot path"

# The station-name vectors: quote-and-system(), and backquotes (which gnuplot runs inside
# double-quoted strings).
for name in "X';system('touch $work/X');print('X" "\`touch $work/X\`"; do
  line_with_a7_named "$name"
  "$ecorail" solve --line line --from A6 --to A8 --time 220 --dwell "$name=30" --plot j.svg \
    > /dev/null 2> err.txt || { echo "FAIL: journey through station $name"; cat err.txt; fail=1; }
  grep -qF "touch $work/X" j.svg || { echo "FAIL: station $name is not drawn as text"; fail=1; }
  check_no_x "station name $name in the speed plot"
  "$ecorail" frontier --line line --from A6 --to "$name" --tmin 100 --tmax 120 --step 10 \
    --plot f.png > /dev/null 2> err.txt ||
    { echo "FAIL: frontier to station $name"; cat err.txt; fail=1; }
  check_no_x "station name $name in the frontier plot"
  rm -f j.svg f.png
done

[ "$fail" -eq 0 ] && echo "plot_injection: ok"
exit "$fail"
