#!/usr/bin/env bash
# Impossible inputs and resource limits, end to end: left unchecked, each would give exit 0
# with nonsense, a crash, an abort inside a library or a run of minutes; each is one line naming
# file/flag and field, exit 2, nothing written, and within seconds.
set -uo pipefail
source "$(dirname "$0")/lib/common.sh" "$@"

run=(solve --from A6 --to A7 --time 110 --json out.json)

# A line with a gradient of 1e308 per mille (once "arrived" in 42.4 s, 670 m short, exit 0).
mkdir line
cp "$src"/data/contest/{stations,gradients,speed_limits,curves}.csv line/
sed -i 's/^12290,12910,3.5/12290,12910,1e308/' line/gradients.csv  # (CRLF lines)
expect_error "gradients.csv: row 35, field 'gradient_permille'" "${run[@]}" --line line
sed -i 's/^12290,12910,1e308/12290,12910,3.5/; s/^91,174,1000/91,174,0.01/' line/curves.csv \
  line/gradients.csv
expect_error "curves.csv: row 3, field 'radius_m'" "${run[@]}" --line line

# Trains: a negative Davis coefficient (once regenerated 77 times its traction, CONVERGENCE),
# no traction at all (once a run "in 0.000 s", 1354 m short), absurd mass and gravity.
train="$src/data/contest/train.toml"
sed 's/^A = .*/A = -50.0/' "$train" > negA.toml
expect_error "negA.toml: field 'davis.A'" "${run[@]}" --train negA.toml
sed 's/coeffs_kN = \[203.0\]/coeffs_kN = [0.0]/' "$train" > zero.toml
expect_error "zero.toml: field 'traction'" "${run[@]}" --train zero.toml
sed 's/^mass_t = .*/mass_t = 1e12/' "$train" > mass.toml
expect_error "mass.toml: field 'mass_t'" "${run[@]}" --train mass.toml
sed 's/^gravity_m_s2 = .*/gravity_m_s2 = 100000.0/' "$train" > gravity.toml
expect_error "gravity.toml: field 'gravity_m_s2'" "${run[@]}" --train gravity.toml
rm -f negA.toml zero.toml mass.toml gravity.toml

# Times that are not finite, or beyond what the engine solves; frontiers of endless points.
expect_error "--time" "${run[@]/110/inf}"
expect_error "--time" "${run[@]/110/1e9}"
expect_error "field '--tmax'" frontier --from A6 --to A7 --tmax nan --json f.json
expect_error "10000 points" frontier --from A6 --to A7 --step 1e-9 --json f.json
expect_error "10000 points" frontier --from A6 --to A7 --tmax 1e9 --json f.json

# Threads: a billion once made libgomp abort asking for 224 GB.
expect_error "--threads" "${run[@]}" --threads 1000000000

# A grid beyond the memory this process can have: refused at once with the estimate.
start=$(date +%s)
(ulimit -v 2000000; expect_error "field '--ds/--dv'" "${run[@]}" --ds 0.01; exit $fail) || fail=1
[ $(($(date +%s) - start)) -lt 20 ] || { echo "FAIL: --ds 0.01 took too long to refuse"; fail=1; }

# Fit points reaching 1e300 km/h once aborted inside Ceres ("Check failed: values != nullptr").
{ echo "speed_kmh,force_kN"; for v in 0 10 20 30 40 50 60; do echo "$v,200"; done; echo "1e300,100"; } \
  > points.csv
expect_error "points.csv: row 9, field 'speed_kmh'" fit-envelope --points points.csv --kind traction
rm -f points.csv

# Policy tables: a device never ends, a directory cannot be read.
expect_error "not a regular file" policy --inspect /dev/zero
mkdir tabledir
expect_error "is a directory" policy --inspect tabledir

[ "$fail" -eq 0 ] && echo "reliability_limits: ok"
exit "$fail"
