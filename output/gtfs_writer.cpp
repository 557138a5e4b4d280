#include "output/gtfs_writer.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <stdexcept>

namespace ecorail::output {

namespace {

// A CSV field, quoted when it holds a comma, a quote or a line break (RFC 4180, as GTFS).
std::string field(const std::string& s) {
  if (s.find_first_of(",\"\r\n") == std::string::npos) return s;
  std::string out = "\"";
  for (const char c : s) {
    if (c == '"') out += '"';
    out += c;
  }
  return out + "\"";
}

long long whole_seconds(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0.0) {
    throw std::invalid_argument("GTFS time: expected a finite time of at least 0 s");
  }
  return std::llround(seconds);
}

}  // namespace

std::vector<GtfsRow> gtfs_rows_of_trip(const physics::Trip& trip, const std::string& train) {
  std::vector<GtfsRow> rows;
  for (const auto& s : trip.stops()) rows.push_back({train, s.station, s.arrival_s, s.departure_s});
  return rows;
}

std::string gtfs_time(double seconds) {
  const long long s = whole_seconds(seconds);
  char buf[32];
  std::snprintf(buf, sizeof buf, "%02lld:%02lld:%02lld", s / 3600, (s / 60) % 60, s % 60);
  return buf;
}

GtfsTables gtfs_tables(const std::vector<GtfsRow>& rows, const GtfsOptions& options) {
  // Trips in order of first appearance; each trip's rows by time.
  std::vector<std::string> trip_order;
  std::map<std::string, std::vector<GtfsRow>> trips;
  std::vector<std::string> stop_order;
  for (const auto& r : rows) {
    if (r.train.empty() || r.station.empty()) {
      throw std::invalid_argument("GTFS rows need a train and a station name");
    }
    whole_seconds(r.arrival_s);
    whole_seconds(r.departure_s);
    if (r.departure_s < r.arrival_s) {
      throw std::invalid_argument("GTFS row of train " + r.train + " at " + r.station +
                                  ": departure before arrival");
    }
    if (!trips.count(r.train)) trip_order.push_back(r.train);
    trips[r.train].push_back(r);
    if (std::find(stop_order.begin(), stop_order.end(), r.station) == stop_order.end()) {
      stop_order.push_back(r.station);
    }
  }
  GtfsTables t;
  t.stops_txt = "stop_id,stop_name\n";
  for (const auto& s : stop_order) t.stops_txt += field(s) + "," + field(s) + "\n";
  t.routes_txt = "route_id,route_short_name,route_long_name,route_type\n" +
                 field(options.route_id) + "," + field(options.route_id) + "," +
                 field(options.route_name) + ",1\n";  // 1 = subway, metro
  t.trips_txt = "route_id,service_id,trip_id\n";
  t.stop_times_txt = "trip_id,arrival_time,departure_time,stop_id,stop_sequence\n";
  for (const auto& id : trip_order) {
    t.trips_txt +=
        field(options.route_id) + "," + field(options.service_id) + "," + field(id) + "\n";
    std::vector<GtfsRow>& visits = trips[id];
    std::stable_sort(visits.begin(), visits.end(),
                     [](const GtfsRow& a, const GtfsRow& b) { return a.arrival_s < b.arrival_s; });
    for (std::size_t i = 0; i < visits.size(); ++i) {
      if (i > 0 && visits[i].arrival_s < visits[i - 1].departure_s) {
        throw std::invalid_argument("GTFS trip " + id + " arrives at " + visits[i].station +
                                    " before it leaves " + visits[i - 1].station);
      }
      t.stop_times_txt += field(id) + "," + gtfs_time(visits[i].arrival_s) + "," +
                          gtfs_time(visits[i].departure_s) + "," + field(visits[i].station) + "," +
                          std::to_string(i + 1) + "\n";
    }
  }
  return t;
}

void add_gtfs_files(data::OutputBatch& batch, const std::filesystem::path& dir,
                    const std::vector<GtfsRow>& rows, const GtfsOptions& options) {
  const GtfsTables t = gtfs_tables(rows, options);
  const std::pair<const char*, const std::string*> files[] = {
      {"stops.txt", &t.stops_txt},
      {"routes.txt", &t.routes_txt},
      {"trips.txt", &t.trips_txt},
      {"stop_times.txt", &t.stop_times_txt}};
  for (const auto& [name, text] : files) {
    batch.add(dir / name, [text = text](std::ostream& out) { out << *text; });
  }
}

}  // namespace ecorail::output
