# Small TTOBench files for the end-to-end scripts (sourced after common.sh, not run by ctest).

# flat_track FILE ID STOPS LIMIT_KMH: a level track with the given stops (a JSON array of
# positions in m) under one speed limit.
flat_track() {
  cat > "$1" <<JSON
{"metadata": {"id": "$2", "library version": "TTOBench v1.4"},
 "stops": {"unit": "m", "values": $3},
 "speed limits": {"units": {"position": "m", "velocity": "km/h"}, "values": [[0, $4]]},
 "gradients": {"units": {"position": "m", "slope": "permil"}, "values": [[0, 0]]}}
JSON
}

# hand_train FILE [EXTRA]: a 200 t train under 2 MW whose every figure is round enough to check
# by hand (power caps, efficiencies 90 % and 80 %, rotating mass 5 %); EXTRA (JSON members with
# a leading comma, e.g. ', "auxiliary power": {...}') replaces the pneumatic brake's line end.
hand_train() {
  cat > "$1" <<JSON
{"metadata": {"id": "hand_train", "library version": "TTOBench v1.4"},
 "mass": {"unit": "t", "value": 200}, "rho": {"unit": "%", "value": 5},
 "max traction power": {"unit": "kW", "value": 2000}, "max reg braking power": {"unit": "kW", "value": 2000},
 "max traction force": {"unit": "kN", "value": 200}, "max reg braking force": {"unit": "kN", "value": 150},
 "max pn braking force": {"unit": "kN", "value": 50}, "max speed": {"unit": "km/h", "value": 100},
 "rolling resistance r0": {"unit": "kN", "value": 2}, "rolling resistance r1": {"unit": "kN/(km/h)", "value": 0.02},
 "rolling resistance r2": {"unit": "kN/(km/h)^2", "value": 0.0005},
 "efficiency traction": {"unit": "%", "value": 90}, "efficiency reg brake": {"unit": "%", "value": 80}${2:-}}
JSON
}
