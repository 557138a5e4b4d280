#!/usr/bin/env bash
# A frontier's JSON records its provenance (program version, line and train with checksums,
# grid, options), and a frontier read back from the cache says so in the table and the JSON.
source "$(dirname "$0")/lib/common.sh" "$@"

args=(frontier --from A6 --to A7 --tmax 95 --cache-dir cache --quiet)
"$ecorail" "${args[@]}" --json cold.json > cold.txt || { echo "FAIL: cold run"; fail=1; }
"$ecorail" "${args[@]}" --json warm.json > warm.txt || { echo "FAIL: warm run"; fail=1; }
grep -q "served from the cache" cold.txt && { echo "FAIL: cold run claims the cache"; fail=1; }
grep -q "served from the cache" warm.txt || { echo "FAIL: warm run does not say it was cached"; fail=1; }
python3 - <<'PY' || fail=1
import json
cold, warm = json.load(open("cold.json")), json.load(open("warm.json"))
assert cold["from_cache"] is False and warm["from_cache"] is True, (cold["from_cache"], warm["from_cache"])
assert cold["points"] == warm["points"]
p = warm["provenance"]
assert p["program"]["name"] == "ecorail" and p["program"]["version"], p["program"]
assert len(p["line"]["checksum"]) == 16 and len(p["train"]["checksum"]) == 16, p
assert p["grid"] == {"ds_m": 5.0, "dv_kmh": 0.2}, p["grid"]
assert p["options"]["from"] == "A6" and p["options"]["tmax_s"] == 95, p["options"]
PY
exit $fail
