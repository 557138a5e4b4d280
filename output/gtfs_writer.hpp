// GTFS export of timetables: stops.txt, routes.txt, trips.txt and stop_times.txt from plain
// rows (train, station, arrival, departure in seconds past the service day's start), so any
// timetable the program makes can be written: a journey now (gtfs_rows_of_journey), the fleet
// timetables (fleet/) later by building the same rows. Times are HH:MM:SS, hours past 24
// allowed as GTFS wants for trips running past midnight; they are rounded to the second with one
// rounding for arrival and departure, so the order of a trip's times is kept. A trip's rows are
// sorted by arrival and numbered 1, 2, ... (stop_sequence). The files are written through an
// OutputBatch: all of them or none. A full feed also needs agency.txt and calendar.txt, which
// depend on the operator and are left to it; stops.txt has no coordinates (lines carry none).
#pragma once

#include <filesystem>
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

struct GtfsOptions {
  std::string route_id = "ecorail";
  std::string route_name = "ecorail line";
  std::string service_id = "weekday";
};

struct GtfsTables {
  std::string stops_txt, routes_txt, trips_txt, stop_times_txt;
};

// The rows of one train's trip: every stop with its arrival and departure on the trip's clock
// (the first stop's arrival is its departure, the last's departure its arrival).
std::vector<GtfsRow> gtfs_rows_of_trip(const physics::Trip& trip, const std::string& train);

// "HH:MM:SS" of a non-negative time past the service day's start, rounded to the second.
std::string gtfs_time(double seconds);
// The four tables; std::invalid_argument for a negative or non-finite time, a departure before
// its arrival, a train that visits a station twice at the same time, or an empty name.
GtfsTables gtfs_tables(const std::vector<GtfsRow>& rows, const GtfsOptions& options = {});
// Writes the four files into directory dir (which must exist) through batch; the caller
// commits.
void add_gtfs_files(data::OutputBatch& batch, const std::filesystem::path& dir,
                    const std::vector<GtfsRow>& rows, const GtfsOptions& options = {});

}  // namespace ecorail::output
