#!/usr/bin/env bash
# `ecorail policy` end to end: writes a table and its CSV, reads it back with --inspect, writes a
# lambda ladder, and turns a truncated or corrupted file, another train or another line into one
# clear error line with exit code 2 (never a crash); failed runs leave no file behind.
set -uo pipefail
source "$(dirname "$0")/lib/common.sh" "$@"

check() {  # check "description" command...
  local what="$1"
  shift
  if ! "$@"; then echo "FAIL: $what"; fail=1; fi
}

# A table and its CSV.
if ! "$ecorail" policy --from A6 --to A7 --time 110 --out a.bin --csv a.csv > out.txt; then
  echo "FAIL: policy run"; cat out.txt; exit 1
fi
check "reported the reload" grep -q "verified by reloading" out.txt
nodes=$(sed -n 's/.* \([0-9]*\) nodes,.*/\1/p' out.txt)
check "node count printed" test -n "$nodes"
check "magic" test "$(head -c 7 a.bin)" = "ECRLPOL"
check "CSV header" test "$(head -n 1 a.csv)" = \
  "layer,lambda_kJ_per_s,stage,s_m,node,v_kmh,control,regime,force_kN,cost_to_go_kJ,time_to_go_s,energy_to_go_kJ"
check "CSV has one row per node" test "$(($(wc -l < a.csv) - 1))" = "$nodes"
check "no temporary files" test -z "$(ls ./*.tmp* 2> /dev/null)"

# Read back and ask for advice.
"$ecorail" policy --inspect a.bin --at 0,0 --at 1300,40 > inspect.txt 2>&1 || {
  echo "FAIL: inspect"; cat inspect.txt; fail=1; }
check "inspect matches" grep -q "matches line 'contest'" inspect.txt
check "start advice" grep -q "at 0.00 m, 0.00 km/h, layer 0: max_traction (full_traction" inspect.txt
check "braking advice" grep -q "at 1300.00 m, 40.00 km/h, layer 0: max_brake (full_brake" inspect.txt

# A ladder: one layer per running time, faster layers with a higher lambda.
"$ecorail" policy --from A6 --to A7 --time 110 --lambda-ladder -5,0,5 --out ladder.bin > ladder.txt ||
  { echo "FAIL: ladder"; cat ladder.txt; fail=1; }
check "three layers" grep -q "3 layer(s)" ladder.txt
lambdas=$(awk '$1 ~ /^[0-9]+$/ && NF == 6 {print $4}' ladder.txt | tr '\n' ' ')
check "lambda falls with the running time ($lambdas)" \
  awk -v l="$lambdas" 'BEGIN { split(l, x, " "); exit !(x[1] > x[2] && x[2] > x[3]) }'
"$ecorail" policy --inspect ladder.bin --at 300,60 > ladder_inspect.txt 2>&1
check "ladder advice per layer" test "$(grep -c '^at 300.00 m' ladder_inspect.txt)" = 3

# Truncated, corrupted, not a table.
head -c 100000 a.bin > truncated.bin
expect_error "truncated" policy --inspect truncated.bin
cp a.bin flipped.bin
printf '\x5a' | dd of=flipped.bin bs=1 seek=2000000 conv=notrunc status=none
expect_error "corrupted: checksum" policy --inspect flipped.bin
expect_error "not an ecorail policy table" policy --inspect a.csv
expect_error "cannot open" policy --inspect missing.bin

# Another train, another line.
sed 's/^mass_t = .*/mass_t = 204.0/' "$src/data/contest/train.toml" > heavy.toml
expect_error "train checksum differs" policy --inspect a.bin --train heavy.toml
mkdir line
cp "$src"/data/contest/{stations,gradients,speed_limits,curves}.csv line/
sed -i '2s/,[^,]*$/,0.5/' line/gradients.csv
expect_error "line checksum differs" policy --inspect a.bin --line line

# Bad requests: clear errors and no file written.
expect_error "minimum running time" policy --from A6 --to A7 --time 50 --out bad.bin
expect_error "--lambda-ladder" policy --from A6 --to A7 --time 110 --lambda-ladder=-200 --out bad.bin
expect_error "--lambda-ladder" policy --from A6 --to A7 --time 110 --lambda-ladder=0,0 --out bad.bin
expect_error "--out" policy --from A6 --to A7 --time 110
expect_error "--out" policy --from A6 --to A7 --time 110 --out nodir/x.bin
expect_error "--at" policy --inspect a.bin --at 300
check "no file from failed runs" test -z "$(ls bad.bin* nodir 2> /dev/null)"

exit $fail
