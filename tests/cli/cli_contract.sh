#!/usr/bin/env bash
# The program's own contract: --version, a misspelt command named with the list of
# commands, CLI11's messages under the program's prefix, advice refused outside the section or
# the train's speeds, and a frontier that starts below the flat-out run refused, not moved.
set -uo pipefail
source "$(dirname "$0")/lib/common.sh" "$@"

"$ecorail" --version > v.txt 2>&1 || { echo "FAIL: --version exit"; fail=1; }
grep -qE '^ecorail [0-9]+\.[0-9]+\.[0-9]+ \(commit [0-9a-f]+|unknown, ' v.txt ||
  { echo "FAIL: --version says"; cat v.txt; fail=1; }
rm -f v.txt

expect_error "unknown command 'solv'; commands: solve, min-time" solv --from A6 --to A7
expect_error "ecorail: error: --time" solve --from A6 --to A7 --time 110 --time 120

"$ecorail" policy --from A6 --to A7 --time 110 --out p.bin > /dev/null || { echo "FAIL: policy"; fail=1; }
expect_error "a position from 0 to the section length 1354 m" policy --inspect p.bin --at=5000,20
expect_error "a position from 0 to the section length 1354 m" policy --inspect p.bin --at=-5,10
expect_error "maximum speed 80 km/h" policy --inspect p.bin --at=300,200
"$ecorail" policy --inspect p.bin --at=300,40 > advice.txt || { echo "FAIL: good --at"; fail=1; }
grep -q "at 300.00 m, 40.00 km/h" advice.txt || { echo "FAIL: no advice"; fail=1; }
rm -f p.bin advice.txt

expect_error "field '--tmin': expected at least the minimum running time of 85.47 s for A6 -> A7" \
  frontier --from A6 --to A7 --tmin 60 --tmax 100 --step 5 --no-cache --json f.json

# frontier checks every output before any work and writes all or none.
expect_error "--plot" frontier --from A6 --to A7 --tmax 100 --step 5 --no-cache --json ok.json --plot nodir/x.svg

[ "$fail" -eq 0 ] && echo "cli_contract: ok"
exit "$fail"
