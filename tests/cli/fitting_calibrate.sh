#!/usr/bin/env bash
# End-to-end: `ecorail calibrate` on the two published per-second tables writes a train file and
# a JSON with davis_A/B/C, rotating_mass_factor, gradient_scale (each with a _se twin) and
# discounted_rows; the gradient scale comes out near zero (the tables do not feel their printed
# gradient). Bad logs (missing column, time going back, too few rows) exit with code 2 and say
# what is wrong, writing nothing.
# Usage: bash fitting_calibrate.sh <path-to-ecorail> <source-dir>
set -euo pipefail
ecorail="$1"
src="$2"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
data="$src/data/contest"

"$ecorail" calibrate --log "$data/seed_profile_A6_A7_110s.csv" \
  --log "$data/seed_profile_A6_A8_220s.csv" --out "$tmp/c.toml" --json "$tmp/c.json" >"$tmp/out"
grep -q "output error" "$tmp/out" || fail "report lacks the output-error section"
grep -q "equation error" "$tmp/out" || fail "report lacks the equation-error section"
grep -q "^\[davis\]" "$tmp/c.toml" || fail "train file lacks [davis]"

python3 - "$tmp/c.json" <<'PY' || fail "JSON checks"
import json, sys
j = json.load(open(sys.argv[1]))
for key in ("davis_A", "davis_B", "davis_C", "rotating_mass_factor", "gradient_scale"):
    assert key in j and key + "_se" in j, f"missing {key} or {key}_se"
    assert j[key + "_se"] is not None and j[key + "_se"] >= 0.0, f"{key}_se = {j[key + '_se']}"
assert isinstance(j["discounted_rows"], list)
assert abs(j["gradient_scale"]) < 0.1, f"gradient_scale {j['gradient_scale']}"
for f in ("equation_error", "output_error"):
    assert abs(j["formulations"][f]["gradient_scale"]) < 0.1
# The typing error of the A6 -> A8 table (00:04:22, distance 2513.7) is found by position.
assert any(p["suspect_row"] == 263 for p in j["position_inconsistencies"]), "typo row not found"
# Coasting deceleration of the fit within 0.01 m/s^2 of the reference Davis curve.
for c in j["coasting_decel_level"]:
    assert abs(c["fitted_m_s2"] - c["base_m_s2"]) < 0.01, c
print("calibrate JSON ok")
PY

# The calibrated train is a valid base train for a second calibration.
"$ecorail" calibrate --log "$data/seed_profile_A6_A7_110s.csv" --train "$tmp/c.toml" \
  --method equation --brief >/dev/null || fail "calibrated train not accepted as --train"

expect_error() {  # expect_error <pattern> <args...>
  local pattern="$1"
  shift
  set +e
  "$ecorail" calibrate "$@" --out "$tmp/bad.toml" --json "$tmp/bad.json" >/dev/null 2>"$tmp/err"
  local rc=$?
  set -e
  [ "$rc" -eq 2 ] || fail "exit $rc, want 2 for $*: $(cat "$tmp/err")"
  grep -q -- "$pattern" "$tmp/err" || fail "message lacks '$pattern': $(cat "$tmp/err")"
  [ ! -e "$tmp/bad.toml" ] && [ ! -e "$tmp/bad.json" ] || fail "output written for bad input"
}
printf 'time_s,speed_kmh\n0,10\n1,11\n' >"$tmp/noforce.csv"
expect_error "traction_force_kN" --log "$tmp/noforce.csv"
printf 'time_s,speed_kmh,traction_force_kN\n0,10,100\n2,11,100\n1,12,100\n' >"$tmp/back.csv"
expect_error "row 4" --log "$tmp/back.csv"
printf 'time_s,speed_kmh,traction_force_kN,braking_force_kN\n0,30,0,0\n1,29.6,0,0\n2,29.2,0,0\n' \
  >"$tmp/short.csv"
expect_error "not identifiable" --log "$tmp/short.csv"
expect_error "davis_A" --log "$tmp/short.csv"
expect_error "--fix" --log "$data/seed_profile_A6_A7_110s.csv" --fix no_such_parameter
echo "fitting_calibrate: ok"
