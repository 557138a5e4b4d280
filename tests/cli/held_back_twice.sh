#!/usr/bin/env bash
# A journey held back twice and then made fast in one part (no earlier than 117 s at 600 m, no
# later than 126 s at 700 m, no earlier than 266 s at 1600 m, no later than 277.1 s at 1800 m):
# every price search misses a window here, and the part's last resort, the time-expanded label
# search (dp/timing_label_search.hpp), meets them. Missed (exit 1) before it. The windows are
# checked on the written re-simulation, and the warning says which search found the run. Its
# energy is checked against an independent witness: a run of a few phases through the same
# windows, simulated below from the hand train's figures (not by ecorail). The label search's
# own run (52 899.6 kJ) is 7.9 % dearer than that witness; re-solved between the states it pins
# where it binds a time (dp/timing_binding_pins.hpp), the run must be no dearer.
set -uo pipefail
source "$(dirname "$0")/lib/common.sh" "$@"
source "$src/tests/cli/lib/ttobench_fixtures.sh"

flat_track track.data flat_3km "[0, 3000]" 80
hand_train train.data
cat > held.json <<'JSON'
{"metadata": {"id": "flat_3km_held_back_twice", "library version": "TTOBench v1.5", "associated track": "flat_3km"},
 "timing points": {"units": {"position": "m", "lower time constraint": "s", "upper time constraint": "s",
   "lower speed constraint": "km/h", "upper speed constraint": "km/h"},
   "values": [[0, 0, 0, 0, 0], [600, 117, null, null, null], [700, null, 126.0, null, null],
              [1600, 266, null, null, null], [1800, null, 277.1, null, null], [3000, null, 700, 0, 0]]}}
JSON
fail=0
"$ecorail" solve --line track.data --train train.data --journey held.json --ds 5 --dv 0.5 \
  --json held_out.json > held.log 2>&1
rc=$?
[ "$rc" -eq 0 ] || { echo "held back twice: exit $rc"; tail -12 held.log; fail=1; }
grep -q "time-expanded label search" held.log || { echo "no label-search warning"; fail=1; }
python3 - held_out.json <<'PY' || fail=1
import json, sys
j = json.load(open(sys.argv[1]))
assert j["windows_met"] is True, j["windows_met"]
# The windows, on the written re-simulation (the tolerance of the journey's options, 0.05 s).
times = {round(w["position_m"]): w["time_s"] for w in j["windows"]}
for pos, lo, hi in [(600, 117, None), (700, None, 126.0), (1600, 266, None), (1800, None, 277.1)]:
    t = times[pos]
    assert lo is None or t >= lo - 0.05, (pos, t)
    assert hi is None or t <= hi + 0.05, (pos, t)
assert times[3000] <= 700.05, times[3000]
PY
grep -q "the time-expanded label search's run is pinned where it binds a time" held.log ||
  { echo "the label search's run was not pinned"; fail=1; }
python3 - held_out.json <<'PY' || fail=1
# The witness: the hand train (200 t, rotating mass 5 %, 200 kN up to 2 MW, resistance
# 2 kN + 0.02 kN/(km/h) v + 0.0005 kN/(km/h)^2 v^2) on the level, integrated by Heun's method
# in time (0.01 s). Full traction to v1, hold to p1, full traction to vA, hold to 600 m; coast
# to 700 m; brake at 0.5 m/s^2 to v2, coast to p2, full traction to vC, hold to 1600 m; coast,
# and brake at 0.5 m/s^2 to rest at 3000 m. The switch points were found by bisection on the
# windows' times (a one-off search over vA and vC, docs/ttobench.md).
import json, sys
M = 200e3 * 1.05
def resistance(v):
    k = 3.6 * v
    return 1e3 * (2 + 0.02 * k + 0.0005 * k * k)
def full(v):
    return min(200e3, 2e6 / max(v, 1e-9))
def coast(v):
    return 0.0
def brake(v):
    return resistance(v) - 0.5 * M
x = v = t = work = 0.0
passed = {}
def step(force, dt=0.01):
    global x, v, t, work
    a1 = (force(v) - resistance(v)) / M
    v1 = max(v + dt * a1, 0.0)
    a2 = (force(v1) - resistance(v1)) / M
    vn = max(v + 0.5 * dt * (a1 + a2), 0.0)
    work += 0.5 * dt * (max(force(v), 0.0) * v + max(force(v1), 0.0) * vn)
    xn = x + 0.5 * dt * (v + vn)
    for s in (600, 700, 1600, 1800):
        if x < s <= xn:
            passed[s] = t + dt * (s - x) / (xn - x)
    x, v, t = xn, vn, t + dt
v1, p1, vA = 5.047666788101196, 541.6208446025848, 11.5
v2, p2, vC = 5.922963189857686, 1375.0164419412613, 18.21
while v < v1: step(full)
while x < p1: step(resistance)
while v < vA: step(full)
while x < 600: step(resistance)
while x < 700: step(coast)
while v > v2: step(brake)
while x < p2: step(coast)
while v < vC: step(full)
while x < 1600: step(resistance)
while x + v * v / (2 * 0.5) < 3000: step(coast)
while v > 0: step(brake)
assert abs(x - 3000) < 0.5 and t <= 700, (x, t)
assert passed[600] >= 117 - 0.05 and passed[700] <= 126.05, passed
assert passed[1600] >= 266 - 0.05 and passed[1800] <= 277.15, passed
witness_kJ = work / 1e3
got = json.load(open(sys.argv[1]))["traction_energy_kJ"]
print(f"traction {got:.1f} kJ, witness {witness_kJ:.1f} kJ ({got / witness_kJ:.4f})")
assert got <= witness_kJ, (got, witness_kJ)
PY
exit $fail
