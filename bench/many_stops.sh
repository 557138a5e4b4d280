#!/usr/bin/env bash
# A TTOBench track of N stops 10 m apart on level track under one speed limit (default 20 003),
# run as one journey of N-1 sections, 20 s each plus 10 s dwells, under /usr/bin/time: all its
# sections are twins (equal track), so they share one transition table and each price is run
# once (dp/section_library.hpp). Usage: bash bench/many_stops.sh build/ecorail [N]
set -euo pipefail
ecorail="${1:-build/ecorail}"
n="${2:-20003}"
dir="$(mktemp -d)"
trap 'rm -rf "$dir"' EXIT
python3 - "$n" > "$dir/many_stops.json" <<'PY'
import json, sys
n = int(sys.argv[1])
print(json.dumps({
    "metadata": {"id": f"many_stops_{n}"},
    "altitude": {"unit": "m", "value": 0},
    "stops": {"unit": "m", "values": [10.0 * i for i in range(n)]},
    "speed limits": {"units": {"position": "m", "velocity": "km/h"}, "values": [[0.0, 80]]},
    "gradients": {"units": {"position": "m", "slope": "permil"}, "values": [[0.0, 0.0]]},
}))
PY
sections=$((n - 1))
/usr/bin/time -f "%e s wall, %U s user, %M KB peak" "$ecorail" solve --line "$dir/many_stops.json" \
  --from S0 --to "S$sections" --time "$((20 * sections))" --dwell 10 --json "$dir/out.json" \
  > "$dir/out.txt"
head -1 "$dir/out.txt"
