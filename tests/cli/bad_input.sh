#!/usr/bin/env bash
# Bad input gets one clear message naming file, row and field, exit code 2, and no output file.
set -uo pipefail
ecorail="$1"
src="$2"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
fail=0

expect_error() {  # expect_error "needle" args...
  local needle="$1"
  shift
  "$ecorail" "$@" --json out.json --csv out.csv > stdout.txt 2> stderr.txt
  local code=$?
  if [ "$code" -ne 2 ]; then
    echo "FAIL: exit $code (want 2): $*"; cat stderr.txt; fail=1
  elif ! grep -qF -- "$needle" stderr.txt; then
    echo "FAIL: message lacks '$needle': $*"; cat stderr.txt; fail=1
  elif [ "$(grep -c . stderr.txt)" -ne 1 ]; then
    echo "FAIL: more than one line of error: $*"; cat stderr.txt; fail=1
  fi
  if ls out.json out.csv out.json.tmp* out.csv.tmp* > /dev/null 2>&1; then
    echo "FAIL: output file left behind: $*"; fail=1
  fi
  rm -f out.json out.csv
}

expect_error "station" solve --from A6 --to A99 --time 110
expect_error "minimum running time" solve --from A6 --to A7 --time 60
expect_error "--time" solve --from A6 --to A7 --time -5
expect_error "nowhere" solve --from A6 --to A7 --time 110 --line nowhere
expect_error "missing.toml" solve --from A6 --to A7 --time 110 --train missing.toml
expect_error "--ds" solve --from A6 --to A7 --time 110 --ds 0

# A line directory with a non-numeric gradient in row 4.
mkdir line
cp "$src"/data/contest/*.csv line/
sed -i '4s/^535,865,12.078/535,865,abc/' line/gradients.csv
expect_error "gradients.csv: row 4, field 'gradient_permille'" solve --from A6 --to A7 --time 110 --line line

# A negative radius.
cp "$src"/data/contest/*.csv line/
sed -i '3s/^91,174,1000/91,174,-1000/' line/curves.csv
expect_error "radius_m" solve --from A6 --to A7 --time 110 --line line

# An output into a directory that does not exist: refused before any work.
"$ecorail" solve --from A6 --to A7 --time 110 --json no/such/dir/out.json > /dev/null 2> err.txt
[ $? -eq 2 ] || { echo "FAIL: missing output dir not exit 2"; fail=1; }

[ "$fail" -eq 0 ] && echo "bad_input: ok"
exit "$fail"
