#!/usr/bin/env bash
# `timetable evaluate --separation` with a separation braking far below the train's own (it
# crashed in the leader look-up): the follower waits at its first stop until the train ahead
# has left the line, exits 0, and never comes closer than its braking distance; with a
# realistic braking, a train length and a safety margin the same invariant holds. Both follower
# modes.
set -uo pipefail
source "$(dirname "$0")/lib/common.sh" "$@"
export XDG_CACHE_HOME="$work/xdg"
mkdir -p "$XDG_CACHE_HOME"
plan=(timetable evaluate --from A6 --to A9 --trip-time 380 --trains 2 --headway 120:660
  --separation --threads 1 --quiet)
for follower in reoptimise supervise; do
  for b in 1e-9 1e-3; do
    "$ecorail" "${plan[@]}" --span 120 --braking "$b" --follower "$follower" --json "s_${follower}_$b.json" \
      > out.txt 2> err.txt
    code=$?
    [ "$code" -eq 0 ] || { echo "FAIL: exit $code with --braking $b --follower $follower"; cat err.txt; fail=1; continue; }
    B="$b" python3 - "s_${follower}_$b.json" <<'PY' || fail=1
import json, os, sys
d = json.load(open(sys.argv[1]))
s = d["separation"]
assert s["cap_exceeded"] is False, s
assert s["min_distance_margin_m"] >= -0.01 and s["min_gap_m"] >= -0.01, s
# With so weak a braking the follower cannot leave A6 before the train ahead has left the line
# at A9 (380 s after its departure, 120 s before the follower's): it waits 260 s there.
if float(os.environ["B"]) <= 1e-6:
    first = [e for e in s["events"] if e["section"] == 1]
    assert first and first[0]["station_wait_s"] >= 380 - 120 - 0.5, s["events"]
    assert s["max_late_s"] > 200, s
PY
  done
done
"$ecorail" "${plan[@]}" --span 120 --train-length 120 --safety-margin 50 --json long.json \
  > out.txt 2> err.txt || { echo "FAIL: train length and margin"; cat err.txt; fail=1; }
python3 - <<'PY' || fail=1
import json
s = json.load(open("long.json"))["separation"]
assert s["cap_exceeded"] is False and s["min_distance_margin_m"] >= -0.01, s
PY
exit $fail
