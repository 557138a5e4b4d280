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

// Coordinates with 6 decimals (about 0.1 m), as GTFS feeds write them.
std::string degrees(double value) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6f", value);
  return buf;
}

bool is_http_url(const std::string& url) {
  for (const char* scheme : {"http://", "https://"}) {
    const std::string s = scheme;
    if (url.size() > s.size() && url.compare(0, s.size(), s) == 0 &&
        url.find_first_of(" \t\r\n\",") == std::string::npos)
      return true;
  }
  return false;
}

// An IANA time zone name: Area/Location (or UTC), letters, digits, '_', '-', '+' and '/'.
bool looks_like_timezone(const std::string& tz) {
  if (tz == "UTC") return true;
  if (tz.empty() || tz.find('/') == std::string::npos || tz.front() == '/' || tz.back() == '/')
    return false;
  for (const char c : tz) {
    const bool ok = (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') ||
                    c == '_' || c == '-' || c == '+' || c == '/';
    if (!ok) return false;
  }
  return tz.find("..") == std::string::npos;
}

bool is_language_code(const std::string& lang) {
  if (lang.size() < 2 || lang.size() > 35) return false;
  for (const char c : lang) {
    if (!((c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '-'))
      return false;
  }
  return true;
}

}  // namespace

bool is_gtfs_date(const std::string& text) {
  if (text.size() != 8) return false;
  for (const char c : text) {
    if (c < '0' || c > '9') return false;
  }
  const int year = std::stoi(text.substr(0, 4));
  const int month = std::stoi(text.substr(4, 2));
  const int day = std::stoi(text.substr(6, 2));
  if (year < 1900 || month < 1 || month > 12 || day < 1) return false;
  static constexpr int kDays[] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
  const bool leap = (year % 4 == 0 && year % 100 != 0) || year % 400 == 0;
  return day <= kDays[month - 1] + (month == 2 && leap ? 1 : 0);
}

std::string gtfs_options_problem(const GtfsOptions& o) {
  if (o.agency_name.empty()) return "agency.txt agency_name: the agency's name; got none";
  if (!is_http_url(o.agency_url))
    return "agency.txt agency_url: a URL starting http:// or https://; got '" + o.agency_url + "'";
  if (!looks_like_timezone(o.agency_timezone))
    return "agency.txt agency_timezone: an IANA time zone such as Europe/Paris; got '" +
           o.agency_timezone + "'";
  if (!is_language_code(o.feed_lang))
    return "feed_info.txt feed_lang: a language code such as en; got '" + o.feed_lang + "'";
  if (!is_gtfs_date(o.start_date))
    return "calendar.txt start_date: a date YYYYMMDD; got '" + o.start_date + "'";
  if (!is_gtfs_date(o.end_date))
    return "calendar.txt end_date: a date YYYYMMDD; got '" + o.end_date + "'";
  if (o.end_date < o.start_date)
    return "calendar.txt end_date: a date not before start_date " + o.start_date + "; got " +
           o.end_date;
  bool any_day = false;
  for (const bool d : o.weekdays) any_day |= d;
  if (!any_day) return "calendar.txt monday..sunday: at least one service weekday; got none";
  if (o.route_id.empty() || o.service_id.empty() || o.agency_id.empty())
    return "route_id, service_id and agency_id: non-empty ids";
  return "";
}

const std::vector<std::string>& gtfs_file_names() {
  static const std::vector<std::string> names{"agency.txt",   "stops.txt",      "routes.txt",
                                              "trips.txt",    "stop_times.txt", "calendar.txt",
                                              "feed_info.txt"};
  return names;
}

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
  if (const std::string problem = gtfs_options_problem(options); !problem.empty()) {
    throw std::invalid_argument("GTFS feed: " + problem);
  }
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
  std::string unlocated;
  for (const auto& s : stop_order) {
    const auto at = options.stop_locations.find(s);
    if (at == options.stop_locations.end() || !(at->second.lat_deg >= -90.0) ||
        !(at->second.lat_deg <= 90.0) || !(at->second.lon_deg >= -180.0) ||
        !(at->second.lon_deg <= 180.0)) {
      unlocated += (unlocated.empty() ? "" : ", ") + s;
    }
  }
  if (!unlocated.empty()) {
    throw std::invalid_argument(
        "GTFS feed: stops.txt stop_lat, stop_lon: coordinates of every "
        "stop; none for " +
        unlocated);
  }
  GtfsTables t;
  t.agency_txt = "agency_id,agency_name,agency_url,agency_timezone,agency_lang\n" +
                 field(options.agency_id) + "," + field(options.agency_name) + "," +
                 field(options.agency_url) + "," + field(options.agency_timezone) + "," +
                 field(options.feed_lang) + "\n";
  t.stops_txt = "stop_id,stop_name,stop_lat,stop_lon,location_type\n";
  for (const auto& s : stop_order) {
    const GtfsStopLocation& at = options.stop_locations.at(s);
    t.stops_txt += field(s) + "," + field(s) + "," + degrees(at.lat_deg) + "," +
                   degrees(at.lon_deg) + ",0\n";  // 0 = a stop or platform
  }
  t.routes_txt = "route_id,agency_id,route_short_name,route_long_name,route_type\n" +
                 field(options.route_id) + "," + field(options.agency_id) + "," +
                 field(options.route_id) + "," + field(options.route_name) +
                 ",1\n";  // 1 = subway, metro
  t.calendar_txt =
      "service_id,monday,tuesday,wednesday,thursday,friday,saturday,sunday,start_date,end_date\n" +
      field(options.service_id);
  for (const bool d : options.weekdays) t.calendar_txt += d ? ",1" : ",0";
  t.calendar_txt += "," + options.start_date + "," + options.end_date + "\n";
  t.feed_info_txt =
      "feed_publisher_name,feed_publisher_url,feed_lang,feed_start_date,feed_end_date" +
      std::string(options.feed_version.empty() ? "" : ",feed_version") + "\n" +
      field(options.agency_name) + "," + field(options.agency_url) + "," +
      field(options.feed_lang) + "," + options.start_date + "," + options.end_date +
      (options.feed_version.empty() ? "" : "," + field(options.feed_version)) + "\n";
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
  const std::string* texts[] = {&t.agency_txt,     &t.stops_txt,    &t.routes_txt,   &t.trips_txt,
                                &t.stop_times_txt, &t.calendar_txt, &t.feed_info_txt};
  const std::vector<std::string>& names = gtfs_file_names();
  for (std::size_t i = 0; i < names.size(); ++i) {
    const std::string* text = texts[i];
    batch.add(dir / names[i], [text](std::ostream& out) { out << *text; });
  }
}

}  // namespace ecorail::output
