// GTFS Schedule export of timetables: a whole feed (agency.txt, stops.txt, routes.txt,
// trips.txt, stop_times.txt, calendar.txt, feed_info.txt) from plain rows (train, station,
// arrival, departure in seconds past the service day's start), so any timetable the program
// makes can be written: a journey (gtfs_rows_of_trip) and the fleet timetables alike. What the
// timetable cannot say comes from GtfsOptions: the agency (name, URL, time zone), the service
// days (a date range and the weekdays it runs) and every stop's coordinates (the stations
// table's lat and lon); a feed missing any of them is refused, never written incomplete. Times
// are HH:MM:SS, hours past 24 allowed as GTFS wants for trips running past midnight; they are
// rounded to the second with one rounding for arrival and departure, so the order of a trip's
// times is kept. A trip's rows are sorted by arrival and numbered 1, 2, ... (stop_sequence).
// The files are written through an OutputBatch: all of them or none.
#pragma once

#include <array>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "data/atomic_file.hpp"
#include "physics/trip.hpp"

namespace ecorail::output {

struct GtfsRow {
  std::string train;    // trip_id
  std::string station;  // stop_id and stop_name
  double arrival_s = 0.0;
  double departure_s = 0.0;
};

struct GtfsStopLocation {
  double lat_deg = 0.0;  // WGS 84
  double lon_deg = 0.0;
};

struct GtfsOptions {
  std::string route_id = "ecorail";
  std::string route_name = "ecorail line";
  std::string service_id = "service";
  std::string agency_id = "ecorail";
  // Required (agency.txt, feed_info.txt): the operator's name, its URL (http:// or https://) and
  // its time zone (an IANA name such as Europe/Paris), in which every time is read.
  std::string agency_name, agency_url, agency_timezone;
  std::string feed_lang = "en";  // IETF BCP 47 code of the feed's text
  std::string feed_version;      // optional
  // Required (calendar.txt): the first and last service day, YYYYMMDD, and the weekdays the
  // timetable runs on, Monday first.
  std::string start_date, end_date;
  std::array<bool, 7> weekdays{true, true, true, true, true, true, true};
  // Required for every stop named in the rows (stops.txt stop_lat, stop_lon).
  std::map<std::string, GtfsStopLocation> stop_locations;
};

struct GtfsTables {
  std::string agency_txt, stops_txt, routes_txt, trips_txt, stop_times_txt, calendar_txt,
      feed_info_txt;
};

// Why options cannot make a feed ("" when they can): the first missing or malformed field,
// named as its GTFS file and field (e.g. "agency.txt agency_url: ...").
std::string gtfs_options_problem(const GtfsOptions& options);
// Whether text is a date YYYYMMDD that exists in the Gregorian calendar.
bool is_gtfs_date(const std::string& text);

// The rows of one train's trip: every stop with its arrival and departure on the trip's clock
// (the first stop's arrival is its departure, the last's departure its arrival).
std::vector<GtfsRow> gtfs_rows_of_trip(const physics::Trip& trip, const std::string& train);

// "HH:MM:SS" of a non-negative time past the service day's start, rounded to the second.
std::string gtfs_time(double seconds);
// The feed's tables; std::invalid_argument for options gtfs_options_problem refuses, a stop
// without coordinates (naming every such stop), a negative or non-finite time, a departure
// before its arrival, a train that visits a station twice at the same time, or an empty name.
GtfsTables gtfs_tables(const std::vector<GtfsRow>& rows, const GtfsOptions& options);
// The names of the files of a feed, in the order they are written.
const std::vector<std::string>& gtfs_file_names();
// Writes the feed's files into directory dir (which must exist) through batch; the caller
// commits.
void add_gtfs_files(data::OutputBatch& batch, const std::filesystem::path& dir,
                    const std::vector<GtfsRow>& rows, const GtfsOptions& options);

}  // namespace ecorail::output
