#!/usr/bin/env bash
# `ecorail timetable`: what the many-train commands refuse and how they end. A supply or a
# section boundary beyond the line, a flag the chosen model does not read, a value given to the
# --separation flag and a time step too fine for the machine are one clear error (exit 2,
# nothing written); a load flow without a solution prints no result line; a heuristic search
# stopped by its move budget says NO_CONVERGENCE with its gap (exit 0), an exact DP CONVERGENCE,
# and a --gap wide enough to cover the proven gap makes the same search CONVERGENCE. A timetable
# given to optimise (--headways, --departures) bounds its result from below in used energy.
set -uo pipefail
source "$(dirname "$0")/lib/common.sh" "$@"

supply="$src/data/contest/power_supply.toml"
small=(--from A6 --to A9 --trains 6 --span 1000 --headway 150:250 --trip-time 480 --quiet)

# Supply and section boundaries beyond the line (the reference line is 22 728 m long).
sed 's/^position_m = 4706.0/position_m = 50000.0/' "$supply" > far_substation.toml
expect_error "50000 m" timetable evaluate "${small[@]}" --model network \
  --power-supply far_substation.toml --json out.json
{ cat "$supply"; printf '\n[[conductors]]\nfrom_m = 99999.0\nconductor_ohm_per_km = 0.008\n'
  printf 'return_ohm_per_km = 0.015\n'; } > far_conductor.toml
expect_error "99999 m" timetable evaluate "${small[@]}" --model network \
  --power-supply far_conductor.toml --json out.json
expect_error "--sections-at" timetable evaluate --quiet --model sections --sections-at 30000 \
  --json out.json

# Flags the chosen model does not use, and a value on the --separation flag.
expect_error "--sections-at" timetable evaluate "${small[@]}" --sections-at 2000 --json out.json
expect_error "--overlap" timetable evaluate "${small[@]}" --overlap either --json out.json
expect_error "--train-length" timetable evaluate "${small[@]}" --train-length 120 --json out.json
expect_error "--separation" timetable evaluate "${small[@]}" --separation=-5 --json out.json

# A grid far finer than any machine holds is refused before it is allocated.
expect_error "--step" timetable evaluate --quiet --step 0.0001 --json out.json

# A load flow with no solution: an error, and no result line on stdout.
sed 's/^conductor_ohm_per_km = 0.008/conductor_ohm_per_km = 1e300/' "$supply" > open_line.toml
"$ecorail" timetable evaluate "${small[@]}" --model network --power-supply open_line.toml \
  --json out.json > stdout.txt 2> stderr.txt
code=$?
if [ "$code" -eq 0 ] || [ -s stdout.txt ] || [ -e out.json ]; then
  echo "FAIL: a load flow without a solution: exit $code, stdout:"; cat stdout.txt; fail=1
fi

# Termination: the annealing's move budget with a proven gap above --gap is NO_CONVERGENCE
# (exit 0, gap in the JSON); a --gap above the proven gap makes it CONVERGENCE; the exact
# overlap DP is CONVERGENCE with a gap of 0.
"$ecorail" timetable optimise "${small[@]}" --moves 2000 --json heuristic.json > /dev/null ||
  { echo "FAIL: heuristic optimise exit $?"; fail=1; }
"$ecorail" timetable optimise "${small[@]}" --moves 2000 --gap 0.99 --json wide.json > /dev/null ||
  { echo "FAIL: optimise --gap 0.99 exit $?"; fail=1; }
"$ecorail" timetable optimise "${small[@]}" --model overlap --json exact.json > /dev/null ||
  { echo "FAIL: exact optimise exit $?"; fail=1; }
python3 - <<'PY' || fail=1
import json
h = json.load(open("heuristic.json")); w = json.load(open("wide.json")); e = json.load(open("exact.json"))
gap = h["gap_fraction_of_substation"]
assert "bound_used_regen_kJ" in h and gap == h["summary"]["gap_fraction_of_substation"], h["summary"]
assert gap > 1e-4 and h["summary"]["termination"] == "NO_CONVERGENCE", (gap, h["summary"])
assert "NO_CONVERGENCE" in h["summary"]["brief_report"] and "gap" in h["summary"]["message"]
assert w["summary"]["termination"] == "CONVERGENCE" and w["substation_energy_kJ"] == h["substation_energy_kJ"]
assert e["summary"]["termination"] == "CONVERGENCE" and e["summary"]["exact"] and e["gap_fraction_of_substation"] == 0
PY

# A timetable to start from (optimise --headways / --departures): the result never uses less
# than it, even when the search alone (no annealing) ends lower; the JSON names what it used.
# A file that breaks the problem, one with --optimise pattern, both flags, and an output that
# would replace it are refused (exit 2, nothing written).
fleet20=(--from A6 --to A9 --trains 20 --span 3800 --headway 150:250 --trip-time 480 --quiet)
"$ecorail" timetable optimise "${fleet20[@]}" --moves 20000 --restarts 4 --json searched.json \
  > /dev/null || { echo "FAIL: optimise --restarts 4 exit $?"; fail=1; }
"$ecorail" timetable optimise "${fleet20[@]}" --restarts 0 --json alone.json > /dev/null ||
  { echo "FAIL: optimise --restarts 0 exit $?"; fail=1; }
python3 - <<'PY' || fail=1
import json
h = json.load(open("searched.json"))
with open("start.csv", "w") as f:
    f.write("headway_s\n" + "".join(f"{x}\n" for x in h["headways_s"]))
with open("start_departures.csv", "w") as f:
    f.write("departure_s\n" + "".join(f"{x}\n" for x in h["departures_s"]))
with open("broken.csv", "w") as f:
    f.write("headway_s\n" + "".join(f"{x}\n" for x in h["headways_s"][:-1] + [h["headways_s"][-1] + 1]))
PY
"$ecorail" timetable optimise "${fleet20[@]}" --restarts 0 --headways start.csv \
  --json given.json > /dev/null || { echo "FAIL: optimise --headways exit $?"; fail=1; }
"$ecorail" timetable optimise "${fleet20[@]}" --restarts 0 --departures start_departures.csv \
  --json given_departures.json > /dev/null || { echo "FAIL: optimise --departures exit $?"; fail=1; }
python3 - <<'PY' || fail=1
import json
h = json.load(open("searched.json")); a = json.load(open("alone.json"))
g = json.load(open("given.json")); d = json.load(open("given_departures.json"))
assert a["used_regen_kJ"] < h["used_regen_kJ"] - 1e-6, (a["used_regen_kJ"], h["used_regen_kJ"])
assert g["used_regen_kJ"] >= h["used_regen_kJ"] - 1e-6, (g["used_regen_kJ"], h["used_regen_kJ"])
assert abs(g["summary"]["given_start_used_regen_kJ"] - h["used_regen_kJ"]) < 1e-6, g["summary"]
assert "given timetable" in g["summary"]["method"], g["summary"]["method"]
assert d["departures_s"] == g["departures_s"] and "given_start_used_regen_kJ" not in a["summary"]
PY
expect_error "broken.csv" timetable optimise "${fleet20[@]}" --headways broken.csv --json out.json
expect_error "--optimise headways" timetable optimise "${fleet20[@]}" --headways start.csv \
  --optimise pattern --json out.json
expect_error "either --headways or --departures" timetable optimise "${fleet20[@]}" \
  --headways start.csv --departures start_departures.csv --json out.json
cp start.csv start_kept.csv
expect_error "start.csv" timetable optimise "${fleet20[@]}" --headways start.csv --csv start.csv
cmp -s start.csv start_kept.csv || { echo "FAIL: the given timetable was overwritten"; fail=1; }

exit $fail
