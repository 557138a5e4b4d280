#!/usr/bin/env bash
# Loop closure: train files written by `ecorail fit-envelope` (from samples of the reference
# envelopes) and by `ecorail calibrate` (from the published tables) are accepted by
# `ecorail solve`, and solving A6 -> A7 in 110 s with them changes the traction energy by less
# than 0.5 % from the reference train's.
# Usage: bash fitting_loop.sh <path-to-ecorail> <source-dir>
set -euo pipefail
ecorail="$1"
src="$2"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
data="$src/data/contest"

"$ecorail" fit-envelope --points "$src/fitting/data/reference_traction_points.csv" \
  --kind traction --out "$tmp/t1.toml" >/dev/null
"$ecorail" fit-envelope --points "$src/fitting/data/reference_braking_points.csv" \
  --kind braking --train "$tmp/t1.toml" --out "$tmp/t.toml" >/dev/null
"$ecorail" calibrate --log "$data/seed_profile_A6_A7_110s.csv" \
  --log "$data/seed_profile_A6_A8_220s.csv" --out "$tmp/c.toml" --brief >/dev/null

"$ecorail" solve --from A6 --to A7 --time 110 --json "$tmp/ref.json" >/dev/null
"$ecorail" solve --from A6 --to A7 --time 110 --train "$tmp/t.toml" --json "$tmp/t.json" \
  >/dev/null || fail "solve rejected the fit-envelope train"
"$ecorail" solve --from A6 --to A7 --time 110 --train "$tmp/c.toml" --json "$tmp/c.json" \
  >/dev/null || fail "solve rejected the calibrated train"

python3 - "$tmp/ref.json" "$tmp/t.json" "$tmp/c.json" <<'PY' || fail "energy changed too much"
import json, sys
ref = json.load(open(sys.argv[1]))["traction_energy_kJ"]
for path, what in ((sys.argv[2], "fitted envelopes"), (sys.argv[3], "calibrated train")):
    e = json.load(open(path))["traction_energy_kJ"]
    change = abs(e / ref - 1.0) * 100.0
    print(f"A6 -> A7, 110 s: reference {ref:.1f} kJ, {what} {e:.1f} kJ, change {change:.3f} %")
    assert change < 0.5, f"{what}: {change:.3f} %"
PY
echo "fitting_loop: ok"
