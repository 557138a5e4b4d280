#!/usr/bin/env bash
# Bad input gets one clear message naming file, row and field, exit code 2, and no output file.
set -uo pipefail
source "$(dirname "$0")/lib/common.sh" "$@"

expect_error "station" solve --from A6 --to A99 --time 110 --json out.json --csv out.csv
expect_error "minimum running time" solve --from A6 --to A7 --time 60 --json out.json --csv out.csv
expect_error "--time" solve --from A6 --to A7 --time -5 --json out.json --csv out.csv
expect_error "nowhere" solve --from A6 --to A7 --time 110 --line nowhere --json out.json --csv out.csv
expect_error "missing.toml" solve --from A6 --to A7 --time 110 --train missing.toml --json out.json --csv out.csv
expect_error "--ds" solve --from A6 --to A7 --time 110 --ds 0 --json out.json --csv out.csv

# A line directory with a non-numeric gradient in row 4.
mkdir line
cp "$src"/data/contest/*.csv line/
sed -i '4s/^535,865,12.078/535,865,abc/' line/gradients.csv
expect_error "gradients.csv: row 4, field 'gradient_permille'" solve --from A6 --to A7 --time 110 --line line --json out.json --csv out.csv

# A negative radius.
cp "$src"/data/contest/*.csv line/
sed -i '3s/^91,174,1000/91,174,-1000/' line/curves.csv
expect_error "radius_m" solve --from A6 --to A7 --time 110 --line line --json out.json --csv out.csv

# An output into a directory that does not exist: refused before any work.
"$ecorail" solve --from A6 --to A7 --time 110 --json no/such/dir/out.json > /dev/null 2> err.txt
[ $? -eq 2 ] || { echo "FAIL: missing output dir not exit 2"; fail=1; }

[ "$fail" -eq 0 ] && echo "bad_input: ok"
exit "$fail"
