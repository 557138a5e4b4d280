#!/usr/bin/env bash
# With an output on standard output ("-") the human report goes to stderr, so stdout is that
# output alone (parsed here as JSON / CSV); a journey's table shows each section's stop error and
# overspeed; every report writes the time price in one format (kJ/s, three decimals).
source "$(dirname "$0")/lib/common.sh" "$@"

"$ecorail" solve --from A6 --to A7 --time 110 --json - > s.json 2> s.err || { echo "FAIL: solve"; fail=1; }
python3 -m json.tool s.json > /dev/null || { echo "FAIL: solve --json - is not pure JSON"; fail=1; }
grep -q "^ecorail solve A6 -> A7" s.err || { echo "FAIL: report not on stderr"; fail=1; }
grep -q "full_traction" s.err || { echo "FAIL: regime table not on stderr"; fail=1; }
grep -Eq "lambda [0-9]+\.[0-9]{3} kJ/s," s.err || { echo "FAIL: lambda format (section)"; cat s.err; fail=1; }

"$ecorail" solve --from A6 --to A8 --time 220 --dwell 30 --json - > j.json 2> j.err ||
  { echo "FAIL: journey"; fail=1; }
python3 -m json.tool j.json > /dev/null || { echo "FAIL: journey --json - is not pure JSON"; fail=1; }
grep -Eq "lambda [0-9]+\.[0-9]{3} kJ/s," j.err || { echo "FAIL: lambda format (journey)"; cat j.err; fail=1; }
python3 - <<'PY' || fail=1
import json, re
j = json.load(open("j.json"))
lines = open("j.err").read().splitlines()
head = next(l for l in lines if l.strip().startswith("section"))
cols = head.split()
assert "stop_err_m" in cols and "overspeed_kmh" in cols, cols
rows = [l.split() for l in lines if re.match(r"\s+A\d+-A\d+\s", l)]
assert len(rows) == 2, rows
for row, sec in zip(rows, j["sections"]):
    assert abs(float(row[cols.index("stop_err_m")]) - sec["stop_error_m"]) < 5e-4, (row, sec["stop_error_m"])
    assert abs(float(row[cols.index("overspeed_kmh")]) - sec["max_overspeed_kmh"]) < 5e-4
# One lambda in the text and in the JSON.
text = float(re.search(r"lambda ([0-9.]+) kJ/s", open("j.err").read()).group(1))
assert abs(text - j["lambda"]) < 5e-4, (text, j["lambda"])
PY

"$ecorail" solve --from A6 --to A7 --time 110 --csv - > c.csv 2> c.err || { echo "FAIL: csv"; fail=1; }
head -1 c.csv | grep -q "^time_hms," || { echo "FAIL: solve --csv - is not the table alone"; fail=1; }
exit $fail
