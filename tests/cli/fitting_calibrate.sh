#!/usr/bin/env bash
# End-to-end: `ecorail calibrate` on the two published per-second tables writes a train file and
# a JSON with davis_A/B/C, rotating_mass_factor, gradient_scale (each with a _se twin) and
# discounted_rows; the gradient scale comes out near zero (the tables do not feel their printed
# gradient). Bad logs (missing column, time going back, too few rows, physically impossible
# rows) exit with code 2 and say what is wrong, writing nothing; a fit that does not converge
# exits with code 1 and writes nothing.
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

# Physically impossible rows are refused before any fit, naming file, row and field: a tenfold
# speed typo (615 km/h for an 80 km/h train) and a speed drop no brake can produce.
awk -F, 'BEGIN { OFS = "," } NR == 40 { $2 = "17083.3"; $3 = "615.0" } { print }' \
  "$data/seed_profile_A6_A7_110s.csv" > "$tmp/typo.csv"
expect_error "typo.csv: row 40, field 'speed_cm_s'" --log "$tmp/typo.csv"
expect_error "maximum speed 80 km/h" --log "$data/seed_profile_A6_A8_220s.csv" --log "$tmp/typo.csv"
awk -F, 'BEGIN { OFS = "," } NR == 40 { $2 = "159.2"; $3 = "5.7" } { print }' \
  "$data/seed_profile_A6_A7_110s.csv" > "$tmp/drop.csv"
expect_error "row 40, field 'speed_cm_s': expected a speed the train can reach from row 39" \
  --log "$tmp/drop.csv"
# A speed of 1e308 m/s (a segmentation fault inside the fit) is refused as well.
printf 'time_s,speed_ms,traction_force_kN\n0,10,100\n1,1e308,100\n2,10,100\n' >"$tmp/huge.csv"
expect_error "huge.csv: row 3, field 'speed_ms'" --log "$tmp/huge.csv"
# Outputs are checked before the fit.
set +e
"$ecorail" calibrate --log "$data/seed_profile_A6_A8_220s.csv" --out "$tmp/no/c.toml" \
  --json "$tmp/nc.json" >/dev/null 2>"$tmp/err"
rc=$?
set -e
[ "$rc" -eq 2 ] && grep -q -- "--out" "$tmp/err" && [ ! -e "$tmp/nc.json" ] ||
  fail "missing --out directory: exit $rc, $(cat "$tmp/err")"

# A fit that ends without convergence is an error and nothing is written.
set +e
"$ecorail" calibrate --log "$data/seed_profile_A6_A8_220s.csv" --max-iterations 1 \
  --out "$tmp/nc.toml" --json "$tmp/nc.json" >"$tmp/out" 2>"$tmp/err"
rc=$?
set -e
[ "$rc" -eq 1 ] || fail "non-converged fit: exit $rc, want 1"
grep -q "NO_CONVERGENCE" "$tmp/err" || fail "message lacks NO_CONVERGENCE: $(cat "$tmp/err")"
[ "$(grep -c . "$tmp/err")" -eq 1 ] || fail "more than one line of error: $(cat "$tmp/err")"
[ ! -e "$tmp/nc.toml" ] && [ ! -e "$tmp/nc.json" ] || fail "non-converged fit was written"
echo "fitting_calibrate: ok"
