#!/usr/bin/env bash
# GTFS export (--gtfs DIR, --gtfs-start) of a journey (`solve`) and of a fleet timetable
# (`timetable evaluate`): the four files, one stop_times row per stop and train in time order,
# times that agree with the JSON/CSV of the same run to the second, the start offset applied;
# bad targets are one error with exit 2 and nothing written.
set -uo pipefail
source "$(dirname "$0")/lib/common.sh" "$@"

mkdir gtfs fleet empty
journey=(solve --from A6 --to A8 --time 300 --dwell 30)
expect_error "--gtfs" "${journey[@]}" --gtfs missing-dir
expect_error "--gtfs" "${journey[@]}" --gtfs -
expect_error "--gtfs-start" "${journey[@]}" --gtfs empty --gtfs-start 5:75:00
expect_error "--gtfs-start" "${journey[@]}" --gtfs empty --gtfs-start soon
expect_error "--gtfs-start" "${journey[@]}" --gtfs empty --gtfs-start .
expect_error "--gtfs-start" "${journey[@]}" --gtfs empty --gtfs-start -60
mkdir empty/stops.txt  # a directory where a GTFS file would go is never replaced
expect_error "--gtfs" "${journey[@]}" --gtfs empty
expect_error "--gtfs" "${journey[@]}" --gtfs . --json stop_times.txt
[ "$(find empty -type f | wc -l)" -eq 0 ] || { echo "FAIL: files written by a refused run"; fail=1; }

"$ecorail" "${journey[@]}" --gtfs gtfs --gtfs-start 05:30:00 --json j.json > /dev/null ||
  { echo "FAIL: solve --gtfs"; fail=1; }
small=(--from A6 --to A9 --trains 6 --span 1000 --headway 150:250 --trip-time 480)
"$ecorail" timetable evaluate "${small[@]}" --csv tt.csv --gtfs fleet > /dev/null ||
  { echo "FAIL: timetable evaluate --gtfs"; fail=1; }

python3 - <<'PY' || fail=1
import csv, json

def rows(path):
    return list(csv.DictReader(open(path, newline="")))

def seconds(hms):
    h, m, s = (int(x) for x in hms.split(":"))
    assert 0 <= m < 60 and 0 <= s < 60, hms
    return 3600 * h + 60 * m + s

# The journey: A6, A7, A8 on one trip, starting at 05:30:00 (19800 s).
j = json.load(open("j.json"))
st = rows("gtfs/stop_times.txt")
assert [r["stop_id"] for r in st] == ["A6", "A7", "A8"], st
assert [int(r["stop_sequence"]) for r in st] == [1, 2, 3], st
assert len(rows("gtfs/trips.txt")) == 1 and len(rows("gtfs/routes.txt")) == 1
assert [r["stop_id"] for r in rows("gtfs/stops.txt")] == ["A6", "A7", "A8"]
assert st[0]["arrival_time"] == st[0]["departure_time"] == "05:30:00", st[0]
times = [seconds(r[k]) - 19800 for r in st for k in ("arrival_time", "departure_time")]
assert times == sorted(times), times
dwell = seconds(st[1]["departure_time"]) - seconds(st[1]["arrival_time"])
assert abs(dwell - 30) <= 1, dwell
total = j["running_time_s"] + 30  # running time plus the one dwell
assert abs(times[-1] - total) <= 0.5 + 1e-9, (times[-1], total)

# The fleet: one trip per train, one row per stop, equal to the timetable CSV to the second.
tt = rows("tt.csv")
st = rows("fleet/stop_times.txt")
trips = [r["trip_id"] for r in rows("fleet/trips.txt")]
assert trips == ["train-%d" % k for k in range(1, 7)], trips
assert len(st) == len(tt) == 6 * 4, (len(st), len(tt))
by_trip = {}
for r in st:
    by_trip.setdefault(r["trip_id"], []).append(r)
for k, trip in enumerate(trips):
    visits = by_trip[trip]
    assert [int(r["stop_sequence"]) for r in visits] == [1, 2, 3, 4]
    mine = [r for r in tt if int(r["train"]) == k + 1]
    assert [r["station"] for r in mine] == [r["stop_id"] for r in visits], (mine, visits)
    for a, g in zip(mine, visits):
        assert abs(float(a["arrival_s"]) - seconds(g["arrival_time"])) <= 0.5 + 1e-9, (a, g)
        assert abs(float(a["departure_s"]) - seconds(g["departure_time"])) <= 0.5 + 1e-9, (a, g)
PY
exit "$fail"
