#!/usr/bin/python3
"""An independent reader of a GTFS Schedule feed (Python's csv module only): checks the files and
fields the GTFS Schedule reference requires, that every id a file names resolves, and that values
are in range. Usage: gtfs_check.py FEED_DIR; exit 0 when valid, 1 with one line per problem."""
import csv
import datetime
import os
import re
import sys

feed = sys.argv[1]
problems = []


def bad(msg):
    problems.append(msg)


def table(name, required):
    path = os.path.join(feed, name)
    if not os.path.isfile(path):
        return None
    with open(path, newline="", encoding="utf-8") as f:
        reader = csv.DictReader(f)
        header = reader.fieldnames or []
        rows = list(reader)
    for field in required:
        if field not in header:
            bad(f"{name}: no column {field}")
    for k, row in enumerate(rows, start=2):
        if None in row or any(v is None for v in row.values()):
            bad(f"{name}: row {k} has a different number of fields than the header")
        for field in required:
            if not (row.get(field) or "").strip():
                bad(f"{name}: row {k}: {field} is empty")
    if not rows:
        bad(f"{name}: no rows")
    return rows


def unique(rows, name, key):
    ids = [r[key] for r in rows]
    if len(ids) != len(set(ids)):
        bad(f"{name}: {key} not unique")
    return set(ids)


def date(text, where):
    try:
        return datetime.datetime.strptime(text, "%Y%m%d").date()
    except (TypeError, ValueError):
        bad(f"{where}: '{text}' is no date YYYYMMDD")
        return None


def seconds(text, where):
    m = re.fullmatch(r"(\d{1,3}):([0-5]\d):([0-5]\d)", text or "")
    if not m:
        bad(f"{where}: '{text}' is no time HH:MM:SS")
        return None
    return 3600 * int(m[1]) + 60 * int(m[2]) + int(m[3])


for name in ("agency.txt", "stops.txt", "routes.txt", "trips.txt", "stop_times.txt"):
    if not os.path.isfile(os.path.join(feed, name)):
        bad(f"required file {name} missing")
if not any(os.path.isfile(os.path.join(feed, n)) for n in ("calendar.txt", "calendar_dates.txt")):
    bad("neither calendar.txt nor calendar_dates.txt")

agency = table("agency.txt", ["agency_name", "agency_url", "agency_timezone"]) or []
stops = table("stops.txt", ["stop_id"]) or []
routes = table("routes.txt", ["route_id", "route_type"]) or []
trips = table("trips.txt", ["route_id", "service_id", "trip_id"]) or []
stop_times = table("stop_times.txt", ["trip_id", "stop_id", "stop_sequence"]) or []
calendar = table("calendar.txt", ["service_id", "monday", "tuesday", "wednesday", "thursday",
                                  "friday", "saturday", "sunday", "start_date", "end_date"])
info = table("feed_info.txt", ["feed_publisher_name", "feed_publisher_url", "feed_lang"])

agency_ids = {a.get("agency_id", "") for a in agency}
if len(agency) > 1 and "" in agency_ids:
    bad("agency.txt: agency_id required when there are several agencies")
for a in agency:
    if not re.fullmatch(r"https?://\S+", a["agency_url"]):
        bad(f"agency.txt: agency_url '{a['agency_url']}' is no URL")
    tz = a["agency_timezone"]
    if os.path.isdir("/usr/share/zoneinfo") and (
            ".." in tz or not os.path.isfile(os.path.join("/usr/share/zoneinfo", tz))):
        bad(f"agency.txt: agency_timezone '{tz}' is no IANA time zone")
if len({a["agency_timezone"] for a in agency}) > 1:
    bad("agency.txt: agencies with different time zones")

stop_ids = unique(stops, "stops.txt", "stop_id")
for s in stops:
    if s.get("location_type", "") in ("", "0", "1", "2"):
        for field in ("stop_name", "stop_lat", "stop_lon"):
            if not s.get(field):
                bad(f"stops.txt: stop {s['stop_id']}: {field} required for its location type")
        try:
            lat, lon = float(s["stop_lat"]), float(s["stop_lon"])
            if not (-90 <= lat <= 90 and -180 <= lon <= 180) or (lat == 0 and lon == 0):
                bad(f"stops.txt: stop {s['stop_id']}: coordinates {lat}, {lon} out of range")
        except (KeyError, TypeError, ValueError):
            bad(f"stops.txt: stop {s['stop_id']}: stop_lat/stop_lon are no numbers")

route_ids = unique(routes, "routes.txt", "route_id")
for r in routes:
    if not (r.get("route_short_name") or r.get("route_long_name")):
        bad(f"routes.txt: route {r['route_id']}: neither route_short_name nor route_long_name")
    if r.get("agency_id", "") not in agency_ids and not (len(agency) == 1 and not r.get("agency_id")):
        bad(f"routes.txt: route {r['route_id']}: agency_id '{r.get('agency_id')}' unknown")
    t = int(r["route_type"]) if r["route_type"].isdigit() else -1
    if not (0 <= t <= 7 or t in (11, 12) or 100 <= t <= 1702):
        bad(f"routes.txt: route_type '{r['route_type']}' is no route type")

service_ids = set()
if calendar is not None:
    service_ids = unique(calendar, "calendar.txt", "service_id")
    for c in calendar:
        for d in ("monday", "tuesday", "wednesday", "thursday", "friday", "saturday", "sunday"):
            if c[d] not in ("0", "1"):
                bad(f"calendar.txt: {d} '{c[d]}' is neither 0 nor 1")
        first = date(c["start_date"], "calendar.txt start_date")
        last = date(c["end_date"], "calendar.txt end_date")
        if first and last and last < first:
            bad("calendar.txt: end_date before start_date")
if os.path.isfile(os.path.join(feed, "calendar_dates.txt")):
    service_ids |= {r["service_id"] for r in table("calendar_dates.txt", ["service_id", "date",
                                                                          "exception_type"]) or []}

trip_ids = unique(trips, "trips.txt", "trip_id")
for t in trips:
    if t["route_id"] not in route_ids:
        bad(f"trips.txt: trip {t['trip_id']}: route_id '{t['route_id']}' unknown")
    if t["service_id"] not in service_ids:
        bad(f"trips.txt: trip {t['trip_id']}: service_id '{t['service_id']}' unknown")

by_trip = {}
for k, st in enumerate(stop_times, start=2):
    if st["trip_id"] not in trip_ids:
        bad(f"stop_times.txt: row {k}: trip_id '{st['trip_id']}' unknown")
    if st["stop_id"] not in stop_ids:
        bad(f"stop_times.txt: row {k}: stop_id '{st['stop_id']}' unknown")
    by_trip.setdefault(st["trip_id"], []).append(st)
for trip in trip_ids:
    visits = by_trip.get(trip, [])
    if len(visits) < 2:
        bad(f"stop_times.txt: trip {trip} has fewer than two stops")
        continue
    sequence = [int(v["stop_sequence"]) for v in visits]
    if sequence != sorted(set(sequence)):
        bad(f"stop_times.txt: trip {trip}: stop_sequence not increasing")
    last = -1
    for i, v in enumerate(visits):
        where = f"stop_times.txt: trip {trip} stop {v['stop_sequence']}"
        if (i == 0 or i == len(visits) - 1) and not (v.get("arrival_time") and v.get("departure_time")):
            bad(f"{where}: the first and last stop need arrival_time and departure_time")
        arr, dep = seconds(v["arrival_time"], where), seconds(v["departure_time"], where)
        if arr is not None and dep is not None:
            if not last <= arr <= dep:
                bad(f"{where}: times out of order")
            last = dep

if info is not None:
    for i in info:
        if not re.fullmatch(r"https?://\S+", i["feed_publisher_url"]):
            bad("feed_info.txt: feed_publisher_url is no URL")
        for field in ("feed_start_date", "feed_end_date"):
            if i.get(field):
                date(i[field], f"feed_info.txt {field}")

for p in problems:
    print(f"{feed}: {p}")
sys.exit(1 if problems else 0)
