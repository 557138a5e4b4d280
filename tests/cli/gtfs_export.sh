#!/usr/bin/env bash
# GTFS export (--gtfs DIR, --gtfs-start, --gtfs-agency ...) of a journey (`solve`) and of a
# fleet timetable (`timetable evaluate`): a valid GTFS Schedule feed, read back by an
# independent reader (tests/cli/lib/gtfs_check.py: every required file and field of the GTFS
# reference, ids that resolve, coordinates and dates in range); one stop_times row per stop and
# train in time order, times that agree with the JSON/CSV of the same run to the second, the
# start offset applied; a new directory is made when its parent exists; a missing agency, time
# zone, service dates or station coordinates, and bad targets, are one error with exit 2 and
# nothing written.
set -uo pipefail
source "$(dirname "$0")/lib/common.sh" "$@"

# The reference line with coordinates (a made-up straight alignment near 48.8 N, 2.3 E; the
# loader reads the optional lat and lon columns of the stations table).
mkdir line
cp "$src"/data/contest/{gradients,speed_limits,curves}.csv line/
awk -F, '{sub(/\r$/, "")} NR == 1 {print $0 ",lat,lon"; next}
         {printf "%s,%.6f,%.6f\n", $0, 48.80 + $2 / 1e6, 2.30 + $2 / 2e6}' \
  "$src/data/contest/stations.csv" > line/stations.csv
agency=(--gtfs-agency "Ligne test" --gtfs-agency-url https://metro.example
  --gtfs-timezone Europe/Paris --gtfs-dates 20270104:20270108 --gtfs-weekdays mon,tue,wed,thu,fri)
feed=(--line line "${agency[@]}")

mkdir fleet empty
journey=(solve --from A6 --to A8 --time 300 --dwell 30)
expect_error "--gtfs" "${journey[@]}" "${feed[@]}" --gtfs missing-parent/dir
expect_error "--gtfs" "${journey[@]}" "${feed[@]}" --gtfs -
# What a feed needs and the command line did not give: one error naming it, before the work.
expect_error "--gtfs-agency" "${journey[@]}" --line line --gtfs empty
expect_error "--gtfs-agency-url" "${journey[@]}" "${feed[@]}" --gtfs-agency-url metro.example --gtfs empty
expect_error "--gtfs-timezone" "${journey[@]}" "${feed[@]}" --gtfs-timezone Mars/Olympus --gtfs empty
expect_error "--gtfs-dates" "${journey[@]}" "${feed[@]}" --gtfs-dates 20270230:20270301 --gtfs empty
expect_error "--gtfs-dates" "${journey[@]}" "${feed[@]}" --gtfs-dates 20270108:20270104 --gtfs empty
expect_error "--gtfs-weekdays" "${journey[@]}" "${feed[@]}" --gtfs-weekdays monday --gtfs empty
# The embedded line has no coordinates: refused, naming the stops without them.
expect_error "none for A6, A7, A8" "${journey[@]}" "${agency[@]}" --gtfs empty
expect_error "--gtfs-start" "${journey[@]}" "${feed[@]}" --gtfs empty --gtfs-start 1e12
expect_error "--gtfs-start" "${journey[@]}" "${feed[@]}" --gtfs empty --gtfs-start 24:00:00
expect_error "--gtfs-start" "${journey[@]}" "${feed[@]}" --gtfs empty --gtfs-start 5:75:00
expect_error "--gtfs-start" "${journey[@]}" "${feed[@]}" --gtfs empty --gtfs-start soon
expect_error "--gtfs-start" "${journey[@]}" "${feed[@]}" --gtfs empty --gtfs-start .
expect_error "--gtfs-start" "${journey[@]}" "${feed[@]}" --gtfs empty --gtfs-start -60
mkdir empty/stops.txt  # a directory where a GTFS file would go is never replaced
expect_error "--gtfs" "${journey[@]}" "${feed[@]}" --gtfs empty
expect_error "--gtfs" "${journey[@]}" "${feed[@]}" --gtfs . --json stop_times.txt
[ "$(find empty -type f | wc -l)" -eq 0 ] || { echo "FAIL: files written by a refused run"; fail=1; }
[ ! -e missing-parent ] && [ ! -e - ] || { echo "FAIL: a refused run made a directory"; fail=1; }

# gtfs does not exist yet: its parent does, so it is made.
"$ecorail" "${journey[@]}" "${feed[@]}" --gtfs gtfs --gtfs-start 05:30:00 --json j.json > /dev/null ||
  { echo "FAIL: solve --gtfs"; fail=1; }
small=(--from A6 --to A9 --trains 6 --span 1000 --headway 150:250 --trip-time 480)
"$ecorail" timetable evaluate "${small[@]}" "${feed[@]}" --csv tt.csv --gtfs fleet > /dev/null ||
  { echo "FAIL: timetable evaluate --gtfs"; fail=1; }
for d in gtfs fleet; do
  /usr/bin/python3 "$src/tests/cli/lib/gtfs_check.py" "$d" || { echo "FAIL: $d is no valid GTFS feed"; fail=1; }
done

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
line = {r["station"]: r for r in rows("line/stations.csv")}
for r in rows("gtfs/stops.txt"):  # the coordinates of the stations table
    assert abs(float(r["stop_lat"]) - float(line[r["stop_id"]]["lat"])) < 1e-6, r
    assert abs(float(r["stop_lon"]) - float(line[r["stop_id"]]["lon"])) < 1e-6, r
assert rows("gtfs/agency.txt")[0]["agency_timezone"] == "Europe/Paris"
cal = rows("gtfs/calendar.txt")[0]
assert [cal[d] for d in ("monday", "friday", "saturday", "sunday")] == ["1", "1", "0", "0"], cal
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
