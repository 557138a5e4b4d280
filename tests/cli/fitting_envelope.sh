#!/usr/bin/env bash
# End-to-end: `ecorail fit-envelope` on samples of the reference envelopes recovers the
# breakpoints 51.5 and 77 km/h within 0.5 km/h, writes a train file and a JSON with the keys
# docs/calibration.md promises, and rejects bad point files with exit code 2.
# Usage: bash fitting_envelope.sh <path-to-ecorail> <source-dir>
set -euo pipefail
ecorail="$1"
src="$2"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

"$ecorail" fit-envelope --points "$src/fitting/data/reference_traction_points.csv" \
  --kind traction --out "$tmp/t.toml" --json "$tmp/t.json" >"$tmp/t.out"
"$ecorail" fit-envelope --points "$src/fitting/data/reference_braking_points.csv" \
  --kind braking --train "$tmp/t.toml" --out "$tmp/tb.toml" --json "$tmp/b.json" >"$tmp/b.out"
grep -q "better fit (lower BIC): piecewise" "$tmp/t.out" || fail "report lacks the form comparison"
[ -s "$tmp/tb.toml" ] || fail "no train file written"
grep -q "^\[traction\]" "$tmp/tb.toml" || fail "train file lacks [traction]"

python3 - "$tmp/t.json" "$tmp/b.json" <<'PY' || fail "JSON checks"
import json, sys
for path, bp in ((sys.argv[1], 51.5), (sys.argv[2], 77.0)):
    j = json.load(open(path))
    for key in ("breakpoint_kmh", "breakpoint_kmh_se", "force_max_kN", "force_max_kN_se",
                "coeffs_kN", "coeffs_kN_se", "residuals", "forms", "better_form"):
        assert key in j, f"{path}: missing {key}"
    assert abs(j["breakpoint_kmh"] - bp) < 0.5, f"{path}: breakpoint {j['breakpoint_kmh']}"
    assert len(j["coeffs_kN"]) == len(j["coeffs_kN_se"]) >= 3
    assert j["form"] == "piecewise" and j["better_form"] == "piecewise"
    assert "power_kW" in j["forms"]["constant_power"]
print("fit-envelope JSON ok")
PY

# Bad input: a missing column and a negative force are exit code 2 with the field named.
printf 'speed_kmh,force\n1,2\n' >"$tmp/bad.csv"
set +e
"$ecorail" fit-envelope --points "$tmp/bad.csv" --kind traction --out "$tmp/x.toml" 2>"$tmp/err"
rc=$?
set -e
[ "$rc" -eq 2 ] || fail "missing column: exit $rc, want 2"
grep -q "force_kN" "$tmp/err" || fail "missing column not named: $(cat "$tmp/err")"
[ ! -e "$tmp/x.toml" ] || fail "a train file was written for bad input"
printf 'speed_kmh,force_kN\n1,2\n2,-3\n' >"$tmp/neg.csv"
set +e
"$ecorail" fit-envelope --points "$tmp/neg.csv" --kind braking 2>"$tmp/err"
rc=$?
set -e
[ "$rc" -eq 2 ] || fail "negative force: exit $rc, want 2"
grep -q "row 3" "$tmp/err" || fail "negative force row not named: $(cat "$tmp/err")"
echo "fitting_envelope: ok"
