// The --gtfs flags of the commands whose result is a timetable (cli/output_options.hpp): the
// feed's options from them, its files as output targets, the stations' coordinates checked
// before the work, and the feed queued in the command's output batch (output/gtfs_writer.hpp).
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "cli/errors.hpp"
#include "cli/output_options.hpp"
#include "data/atomic_file.hpp"
#include "data/csv_reader.hpp"
#include "data/input_error.hpp"
#include "output/gtfs_writer.hpp"

namespace ecorail::cli {

void add_gtfs_options(CLI::App* cmd, OutputOptions& o) {
  cmd->add_option("--gtfs", o.gtfs,
                  "write the timetable as a GTFS feed into this directory (made if its parent "
                  "exists): agency, stops, routes, trips, stop_times, calendar, feed_info; needs "
                  "--gtfs-agency, --gtfs-agency-url, --gtfs-timezone, --gtfs-dates and station "
                  "coordinates (lat, lon in the stations table)");
  cmd->add_option("--gtfs-start", o.gtfs_start,
                  "clock time of t = 0 in the GTFS files (HH:MM:SS or seconds, below 24 h)")
      ->capture_default_str();
  cmd->add_option("--gtfs-agency", o.gtfs_agency, "GTFS: the operating agency's name");
  cmd->add_option("--gtfs-agency-url", o.gtfs_agency_url,
                  "GTFS: the agency's URL (http:// or https://)");
  cmd->add_option("--gtfs-timezone", o.gtfs_timezone,
                  "GTFS: the agency's time zone, an IANA name such as Europe/Paris");
  cmd->add_option("--gtfs-dates", o.gtfs_dates,
                  "GTFS: first and last service day, YYYYMMDD:YYYYMMDD");
  cmd->add_option("--gtfs-weekdays", o.gtfs_weekdays,
                  "GTFS: the weekdays the timetable runs on, e.g. mon,tue,wed,thu,fri")
      ->capture_default_str();
  cmd->add_option("--gtfs-lang", o.gtfs_lang, "GTFS: the feed's language code")
      ->capture_default_str();
}

namespace {

// The feed's options from the --gtfs-* flags; InputError naming the first flag that is missing
// or malformed.
output::GtfsOptions gtfs_feed_options(const OutputOptions& o) {
  output::GtfsOptions f;
  f.agency_name = o.gtfs_agency;
  f.agency_url = o.gtfs_agency_url;
  f.agency_timezone = o.gtfs_timezone;
  f.feed_lang = o.gtfs_lang;
  f.feed_version = "ecorail";
  if (f.agency_name.empty())
    bad("--gtfs-agency", "the agency's name with --gtfs (agency.txt agency_name); got none");
  if (f.agency_url.empty())
    bad("--gtfs-agency-url",
        "the agency's URL with --gtfs (agency.txt agency_url, http:// or https://); got none");
  if (f.agency_timezone.empty())
    bad("--gtfs-timezone",
        "the agency's time zone with --gtfs (agency.txt agency_timezone, an IANA name such "
        "as Europe/Paris); got none");
  std::error_code ec;
  if (std::filesystem::is_directory("/usr/share/zoneinfo", ec) &&
      (f.agency_timezone.find("..") != std::string::npos ||
       !std::filesystem::is_regular_file("/usr/share/zoneinfo/" + f.agency_timezone, ec)))
    bad("--gtfs-timezone",
        "an IANA time zone such as Europe/Paris; got '" + f.agency_timezone + "'");
  if (o.gtfs_dates.empty())
    bad("--gtfs-dates",
        "the first and last service day with --gtfs (calendar.txt), YYYYMMDD:YYYYMMDD; got "
        "none");
  const auto colon = o.gtfs_dates.find(':');
  f.start_date = o.gtfs_dates.substr(0, colon);
  f.end_date = colon == std::string::npos ? "" : o.gtfs_dates.substr(colon + 1);
  if (!output::is_gtfs_date(f.start_date) || !output::is_gtfs_date(f.end_date) ||
      f.end_date < f.start_date)
    bad("--gtfs-dates",
        "two dates YYYYMMDD:YYYYMMDD, the first not after the second; got '" + o.gtfs_dates + "'");
  f.weekdays.fill(false);
  static const char* kDays[] = {"mon", "tue", "wed", "thu", "fri", "sat", "sun"};
  std::stringstream days(o.gtfs_weekdays);
  for (std::string day; std::getline(days, day, ',');) {
    const auto at =
        std::find_if(std::begin(kDays), std::end(kDays), [&](const char* d) { return day == d; });
    if (at == std::end(kDays))
      bad("--gtfs-weekdays",
          "weekdays among mon,tue,wed,thu,fri,sat,sun, separated by commas; got '" +
              o.gtfs_weekdays + "'");
    f.weekdays[static_cast<std::size_t>(at - std::begin(kDays))] = true;
  }
  if (const std::string problem = output::gtfs_options_problem(f); !problem.empty()) {
    const char* flag = problem.rfind("feed_info.txt feed_lang", 0) == 0      ? "--gtfs-lang"
                       : problem.rfind("agency.txt agency_url", 0) == 0      ? "--gtfs-agency-url"
                       : problem.rfind("agency.txt agency_timezone", 0) == 0 ? "--gtfs-timezone"
                       : problem.rfind("calendar.txt monday", 0) == 0        ? "--gtfs-weekdays"
                                                                             : "--gtfs";
    bad(flag, problem);
  }
  return f;
}

}  // namespace

std::vector<OutputTarget> gtfs_targets(const OutputOptions& o) {
  const std::string& dir = o.gtfs;
  if (dir.empty()) return {};
  gtfs_start_s(o.gtfs_start);
  gtfs_feed_options(o);
  std::error_code ec;
  bool new_directory = false;
  if (data::is_stdout_path(dir) || !std::filesystem::is_directory(dir, ec)) {
    std::filesystem::path parent = std::filesystem::path(dir).parent_path();
    if (parent.empty()) parent = ".";
    if (data::is_stdout_path(dir) ||
        std::filesystem::exists(std::filesystem::symlink_status(dir, ec)) ||
        !std::filesystem::is_directory(parent, ec)) {
      throw data::InputError("command line", 0, "--gtfs",
                             "a directory for the GTFS feed, existing or new in an existing "
                             "directory; got '" +
                                 dir + "'");
    }
    // The new directory is an entry of its parent, as a file would be: the parent must be
    // writable.
    if (const std::string problem = data::output_target_problem(dir); !problem.empty()) {
      throw data::InputError("command line", 0, "--gtfs",
                             "a directory that can be made; " + problem);
    }
    new_directory = true;
  }
  std::vector<OutputTarget> targets;
  for (const std::string& name : output::gtfs_file_names()) {
    targets.push_back(
        {"--gtfs", (std::filesystem::path(dir) / name).string(), false, new_directory});
  }
  return targets;
}

double gtfs_start_s(const std::string& text) {
  const std::string expected =
      "a clock time HH:MM:SS, HH:MM or a number of seconds, from 0 to below 24 h";
  double seconds = -1.0;
  if (text.find(':') != std::string::npos) {
    seconds = data::parse_clock_s(text, data::TwoFieldClock::HoursMinutes, "command line", 0,
                                  "--gtfs-start", expected);
  } else {
    try {
      seconds = data::parse_number(text, "command line", 0, "--gtfs-start");
    } catch (const data::InputError&) {
    }
  }
  if (!(seconds >= 0.0 && seconds < 86400.0))
    throw data::InputError("command line", 0, "--gtfs-start", expected + "; got '" + text + "'");
  return seconds;
}

void check_gtfs_stops(const OutputOptions& o, const data::Line& line,
                      const std::vector<std::string>& stops) {
  if (o.gtfs.empty()) return;
  std::string missing;
  for (const std::string& name : stops) {
    const auto at = std::find_if(line.stations.begin(), line.stations.end(),
                                 [&](const data::Station& s) { return s.name == name; });
    if (at == line.stations.end() || !at->has_coordinates())
      missing += (missing.empty() ? "" : ", ") + name;
  }
  if (!missing.empty()) {
    const std::string table = line.stations_file.empty() ? "the line" : line.stations_file;
    throw data::InputError(table, 0, "lat/lon",
                           "coordinates of every stop for --gtfs (GTFS stops.txt stop_lat, "
                           "stop_lon); none for " +
                               missing);
  }
}

void add_gtfs_outputs(data::OutputBatch& batch, const OutputOptions& o,
                      const std::vector<std::pair<std::string, physics::Trip>>& trips,
                      const data::Line& line) {
  if (o.gtfs.empty()) return;
  const double start_s = gtfs_start_s(o.gtfs_start);
  output::GtfsOptions feed = gtfs_feed_options(o);
  std::vector<output::GtfsRow> rows;
  std::vector<std::string> stops;
  for (const auto& [id, trip] : trips) {
    for (output::GtfsRow row : output::gtfs_rows_of_trip(trip, id)) {
      row.arrival_s += start_s;
      row.departure_s += start_s;
      if (std::find(stops.begin(), stops.end(), row.station) == stops.end())
        stops.push_back(row.station);
      rows.push_back(std::move(row));
    }
  }
  check_gtfs_stops(o, line, stops);
  for (const data::Station& s : line.stations) {
    if (s.has_coordinates()) feed.stop_locations[s.name] = {s.lat_deg, s.lon_deg};
  }
  std::error_code ec;
  if (!std::filesystem::is_directory(o.gtfs, ec)) {
    std::filesystem::create_directory(o.gtfs, ec);  // its parent was checked before the work
    if (ec) throw std::runtime_error("cannot make directory " + o.gtfs + ": " + ec.message());
  }
  output::add_gtfs_files(batch, o.gtfs, rows, feed);
}

}  // namespace ecorail::cli
