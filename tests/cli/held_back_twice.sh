#!/usr/bin/env bash
# A journey held back twice and then made fast in one part (no earlier than 117 s at 600 m, no
# later than 126 s at 700 m, no earlier than 266 s at 1600 m, no later than 277.1 s at 1800 m):
# every price search misses a window here, and the part's last resort, the time-expanded label
# search (dp/timing_label_search.hpp), meets them. Missed (exit 1) before it. The windows are
# checked on the written re-simulation, and the warning says which search found the run.
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
exit $fail
