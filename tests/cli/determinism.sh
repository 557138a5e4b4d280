#!/usr/bin/env bash
# Determinism: the same inputs give the same bytes with 1 and 2 threads, and two
# runs at the same time give the same bytes as one alone, for sections, journeys, frontiers and
# the fleet commands (timetable evaluate and optimise, also on the DC network model) and a
# delay recovery. Only the wall times and the thread count differ in a JSON report (keys with
# "wall" or "threads", and a brief report's wall time); they are removed before comparing,
# nothing else is.
set -uo pipefail
source "$(dirname "$0")/lib/common.sh" "$@"

# strip FILE: the JSON without wall-clock and thread-count keys, canonically printed.
strip() {
  python3 - "$1" <<'PY'
import json, re, sys
def clean(x):
    if isinstance(x, dict):
        return {k: clean(v) for k, v in x.items() if not re.search(r"wall|threads", k)}
    if isinstance(x, list):
        return [clean(v) for v in x]
    # A brief report's wall time ends it ("..., 48.41 s") or its figures, before the reason a
    # search stopped ("..., 1.24 s; the search ended ...").
    if isinstance(x, str):
        return re.sub(r"[0-9.]+ s( wall)?(?=(, [A-Z_]+)?(;|$))", "", x)
    return x
print(json.dumps(clean(json.load(open(sys.argv[1]))), sort_keys=True))
PY
}

# same NAME ARGS...: runs ARGS with --threads 1, with --threads 2, and twice side by side with
# --threads 2; every JSON (stripped) and CSV must be identical.
same() {
  local name="$1"
  shift
  "$ecorail" "$@" --threads 1 --json "$name.1.json" --csv "$name.1.csv" > /dev/null 2> err.txt ||
    { echo "FAIL: $name (1 thread)"; cat err.txt; fail=1; return; }
  "$ecorail" "$@" --threads 2 --json "$name.2.json" --csv "$name.2.csv" > /dev/null 2>&1 &
  local a=$!
  "$ecorail" "$@" --threads 2 --json "$name.3.json" --csv "$name.3.csv" > /dev/null 2>&1
  wait "$a" || { echo "FAIL: $name (concurrent)"; fail=1; return; }
  for k in 2 3; do
    [ "$(strip "$name.1.json")" = "$(strip "$name.$k.json")" ] ||
      { echo "FAIL: $name JSON differs (run $k)"; fail=1; }
    cmp -s "$name.1.csv" "$name.$k.csv" || { echo "FAIL: $name CSV differs (run $k)"; fail=1; }
  done
}

same section solve --from A6 --to A7 --time 110
same journey solve --from A6 --to A8 --time 220 --dwell A7=45
same frontier frontier --from A6 --to A7 --tmax 100 --step 2 --no-cache
fleet=(--from A6 --to A8 --trains 4 --span 600 --headway 150:250 --trip-time 300)
same evaluate timetable evaluate "${fleet[@]}" --uniform
same optimise timetable optimise "${fleet[@]}"
supply=(--model network --power-supply "$src/data/contest/power_supply.toml")
same network_evaluate timetable evaluate "${fleet[@]}" --uniform "${supply[@]}"
same network_optimise timetable optimise "${fleet[@]}" "${supply[@]}" --moves 300
"$ecorail" timetable evaluate --from A6 --to A9 --trains 4 --span 600 --headway 150:250 \
  --trip-time 400 --uniform --csv plan.csv --quiet > /dev/null || { echo "FAIL: plan"; fail=1; }
same delay delay --plan plan.csv --train 2 --station A6 --delay 20

[ "$fail" -eq 0 ] && echo "determinism: ok"
exit "$fail"
