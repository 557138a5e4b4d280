#!/usr/bin/env bash
# `ecorail export`: the line and the train as TTOBench JSON. What is written drives the same:
# a journey on the exported reference line costs what it costs on the embedded line, and a
# TTOBench track and train written back out solve as the originals and export to the same
# text again. What TTOBench cannot state (the reference train's polynomial envelopes) is one
# error with exit 2, and then nothing is written, not even the track asked for beside it.
set -uo pipefail
source "$(dirname "$0")/lib/common.sh" "$@"
tto="$src/../shared/data/ttobench"

expect_error "--ttobench-track" export
expect_error "--ttobench-train" export --ttobench-track line.json --ttobench-train train.json
expect_error "--ttobench-track" export --ttobench-track .

energy() {  # energy JSON: traction kJ of a solve's JSON report
  python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["traction_energy_kJ"])' "$1"
}
same() {  # same A B WHAT: A and B agree to 1e-9 relative
  python3 -c 'import sys; a, b = float(sys.argv[1]), float(sys.argv[2]); sys.exit(abs(a - b) > 1e-9 * abs(a))' "$1" "$2" ||
    { echo "FAIL: $3: $1 vs $2"; fail=1; }
}

# The reference line: a journey A6 -> A9 with stops, on the embedded line and on its export.
"$ecorail" export --ttobench-track line.json > out.txt || { echo "FAIL: export the line"; fail=1; }
grep -q "14 stops, 22728.0 m" out.txt || { echo "FAIL: export summary"; cat out.txt; fail=1; }
run=(solve --from A6 --to A9 --time 400 --dwell 30 --quiet)
"$ecorail" "${run[@]}" --json a.json > /dev/null || { echo "FAIL: solve embedded"; fail=1; }
"$ecorail" "${run[@]}" --line line.json --json b.json > /dev/null || { echo "FAIL: solve exported"; fail=1; }
same "$(energy a.json)" "$(energy b.json)" "journey A6 -> A9 on the exported reference line"

# A TTOBench track and train: written back, they solve alike and export to the same text.
if [ -d "$tto" ]; then
  track="$tto/tracks/00_reference_with_tunnels.json"
  train="$tto/trains/CH_Stadler_FLIRT_TPF.json"
  "$ecorail" export --line "$track" --train "$train" --ttobench-track t1.json --ttobench-train r1.json \
    > /dev/null || { echo "FAIL: export a TTOBench pair"; fail=1; }
  "$ecorail" export --line t1.json --train r1.json --ttobench-track t2.json --ttobench-train r2.json \
    --track-id 00_reference_with_tunnels > /dev/null || { echo "FAIL: export the export"; fail=1; }
  cmp -s r1.json r2.json || { echo "FAIL: the train's export is not a fixed point"; fail=1; }
  grep -v '"metadata"' t1.json > t1.body
  grep -v '"metadata"' t2.json > t2.body
  cmp -s t1.body t2.body || { echo "FAIL: the track's export is not a fixed point"; fail=1; }
  tr=(solve --from S0 --to S1 --time 400 --quiet)
  "$ecorail" "${tr[@]}" --line "$track" --train "$train" --json c.json > /dev/null 2>&1 ||
    { echo "FAIL: solve the TTOBench pair"; fail=1; }
  "$ecorail" "${tr[@]}" --line t1.json --train r1.json --json d.json > /dev/null 2>&1 ||
    { echo "FAIL: solve the exported pair"; fail=1; }
  same "$(energy c.json)" "$(energy d.json)" "S0 -> S1 on the exported TTOBench pair"
fi
exit "$fail"
