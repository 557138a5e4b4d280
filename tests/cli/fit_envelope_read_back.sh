#!/usr/bin/env bash
# fit-envelope reads the train it would write back through the loader `solve` uses: points
# whose forces are all 0 fit "converged" to a zero envelope, a train that cannot start; that is
# one error naming the points file (exit 2) and neither --out nor --json is written. Good points
# still make a train that solve runs.
set -uo pipefail
source "$(dirname "$0")/lib/common.sh" "$@"

printf 'speed_kmh,force_kN\n0,0\n10,0\n20,0\n30,0\n40,0\n50,0\n60,0\n70,0\n80,0\n' > zero.csv
expect_error "zero.csv" fit-envelope --points zero.csv --kind traction --out t.toml --json f.json
grep -q "would refuse" stderr.txt || { echo "FAIL: the message does not say why"; cat stderr.txt; fail=1; }
[ "$(grep -o expected stderr.txt | wc -l)" -eq 1 ] || { echo "FAIL: 'expected' twice"; fail=1; }
expect_error "zero.csv" fit-envelope --points zero.csv --kind braking --out t.toml
expect_error "zero.csv" fit-envelope --points zero.csv --kind traction --json f.json

# Points of a real envelope: written, and solve runs the train.
printf 'speed_kmh,force_kN\n0,310\n10,310\n20,310\n30,310\n40,300\n50,240\n60,200\n70,171\n80,150\n' \
  > good.csv
"$ecorail" fit-envelope --points good.csv --kind traction --out t.toml > /dev/null ||
  { echo "FAIL: fit-envelope of good points"; fail=1; }
"$ecorail" solve --from A6 --to A7 --time 110 --train t.toml > /dev/null ||
  { echo "FAIL: solve refuses the fitted train"; fail=1; }
exit "$fail"
