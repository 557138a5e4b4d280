#include "cli/output_options.hpp"

#include <algorithm>
#include <filesystem>
#include <sstream>
#include <stdexcept>

#include "data/atomic_file.hpp"
#include "data/csv_reader.hpp"
#include "data/input_error.hpp"
#include "output/gnuplot.hpp"
#include "output/gtfs_writer.hpp"
#include "output/provenance.hpp"
#include "output/run_json.hpp"
#include "output/solve_reports.hpp"
#include "output/speed_plot.hpp"

namespace ecorail::cli {

namespace {

// Two spellings of one file (a/../b, ./b, a link to a directory) compare equal.
std::filesystem::path identity(const std::string& path) {
  if (data::is_stdout_path(path)) return "-";
  std::error_code ec;
  const auto canonical = std::filesystem::weakly_canonical(std::filesystem::absolute(path), ec);
  return ec ? std::filesystem::absolute(path).lexically_normal() : canonical;
}

std::string objective_text(const std::string& name) {
  if (name == "traction") return "least traction energy (work at the wheel / traction efficiency)";
  if (name == "net") return "least net energy (traction input - regenerated)";
  return name;
}

output::SpeedPlotLabels plot_labels(const OutputOptions& o, const nlohmann::json& report) {
  output::SpeedPlotLabels labels;
  labels.x_axis = o.plot_x == "time" ? output::PlotAxis::Time : output::PlotAxis::Distance;
  if (report.contains("stops") && report["stops"].is_array()) {
    for (const auto& s : report["stops"]) labels.stations.push_back(s.get<std::string>());
  } else if (report.contains("from") && report.contains("to")) {
    labels.stations = {report["from"].get<std::string>(), report["to"].get<std::string>()};
  }
  std::string objective;
  if (report.contains("objective") && report["objective"].is_string()) {
    objective = report["objective"].get<std::string>();
  } else if (const auto ptr = nlohmann::json::json_pointer("/provenance/options/objective");
             report.contains(ptr) && report[ptr].is_string()) {
    objective = report[ptr].get<std::string>();
  }
  labels.objective = objective_text(objective);
  return labels;
}

}  // namespace

void add_output_options(CLI::App* cmd, OutputOptions& o) {
  cmd->add_option("--json", o.json, "write the result as JSON ('-': standard output)");
  cmd->add_option("--csv", o.csv, "write the per-second table as CSV ('-': standard output)");
  cmd->add_option("--xlsx", o.xlsx, "write the per-second table and a summary as XLSX");
  cmd->add_option("--plot", o.plot,
                  "write the speed plot (gnuplot): FILE.svg or FILE.png ('-': SVG on standard "
                  "output)");
  cmd->add_option("--plot-x", o.plot_x, "horizontal axis of the speed plot: distance or time")
      ->check(CLI::IsMember({"distance", "time"}))
      ->capture_default_str();
}

void input_files(CLI::App* cmd, std::initializer_list<const char*> flags) {
  for (const char* flag : flags) {
    CLI::Option* option = nullptr;
    try {
      option = cmd->get_option(flag);
    } catch (const CLI::OptionNotFound&) {
      throw std::logic_error(std::string("input_files: ") + cmd->get_name() + " has no " + flag);
    }
    const std::string name = flag;
    option->each([name](const std::string& path) { data::register_input(name, path); });
  }
}

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

[[noreturn]] void bad_gtfs(const char* flag, const std::string& expected) {
  throw data::InputError("command line", 0, flag, expected);
}

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
    bad_gtfs("--gtfs-agency", "the agency's name with --gtfs (agency.txt agency_name); got none");
  if (f.agency_url.empty())
    bad_gtfs("--gtfs-agency-url",
             "the agency's URL with --gtfs (agency.txt agency_url, http:// or https://); got none");
  if (f.agency_timezone.empty())
    bad_gtfs("--gtfs-timezone",
             "the agency's time zone with --gtfs (agency.txt agency_timezone, an IANA name such "
             "as Europe/Paris); got none");
  std::error_code ec;
  if (std::filesystem::is_directory("/usr/share/zoneinfo", ec) &&
      (f.agency_timezone.find("..") != std::string::npos ||
       !std::filesystem::is_regular_file("/usr/share/zoneinfo/" + f.agency_timezone, ec)))
    bad_gtfs("--gtfs-timezone",
             "an IANA time zone such as Europe/Paris; got '" + f.agency_timezone + "'");
  if (o.gtfs_dates.empty())
    bad_gtfs("--gtfs-dates",
             "the first and last service day with --gtfs (calendar.txt), YYYYMMDD:YYYYMMDD; got "
             "none");
  const auto colon = o.gtfs_dates.find(':');
  f.start_date = o.gtfs_dates.substr(0, colon);
  f.end_date = colon == std::string::npos ? "" : o.gtfs_dates.substr(colon + 1);
  if (!output::is_gtfs_date(f.start_date) || !output::is_gtfs_date(f.end_date) ||
      f.end_date < f.start_date)
    bad_gtfs("--gtfs-dates", "two dates YYYYMMDD:YYYYMMDD, the first not after the second; got '" +
                                 o.gtfs_dates + "'");
  f.weekdays.fill(false);
  static const char* kDays[] = {"mon", "tue", "wed", "thu", "fri", "sat", "sun"};
  std::stringstream days(o.gtfs_weekdays);
  for (std::string day; std::getline(days, day, ',');) {
    const auto at =
        std::find_if(std::begin(kDays), std::end(kDays), [&](const char* d) { return day == d; });
    if (at == std::end(kDays))
      bad_gtfs("--gtfs-weekdays",
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
    bad_gtfs(flag, problem);
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

void check_output_targets(const std::vector<OutputTarget>& targets) {
  std::vector<std::pair<std::filesystem::path, std::string>> seen;
  std::vector<output::PlotFormat> checked_formats;  // gnuplot is asked once per format
  for (const auto& t : targets) {
    if (t.path.empty()) continue;
    // A file in a directory still to be made: only the run's inputs could be in its way.
    const std::string problem = t.new_directory ? (data::input_read_as(t.path).empty()
                                                       ? ""
                                                       : "'" + t.path + "' is an input of this run")
                                                : data::output_target_problem(t.path);
    if (!problem.empty()) {
      throw data::InputError("command line", 0, t.flag,
                             "a file that can be written or replaced; " + problem);
    }
    const auto id = identity(t.path);
    for (const auto& [other, flag] : seen) {
      if (other == id) {
        throw data::InputError("command line", 0, t.flag,
                               "a path other than " + flag + "'s; got '" + t.path + "' twice");
      }
    }
    seen.emplace_back(id, t.flag);
    if (t.plot) {
      if (!output::plot_format_for(t.path)) {
        throw data::InputError("command line", 0, t.flag,
                               "a plot file ending in .svg or .png; got '" + t.path + "'");
      }
      const auto format = *output::plot_format_for(t.path);
      if (std::find(checked_formats.begin(), checked_formats.end(), format) ==
          checked_formats.end()) {
        if (const std::string problem = output::gnuplot_problem(format); !problem.empty()) {
          throw data::InputError("command line", 0, t.flag, "a plot gnuplot can draw; " + problem);
        }
        checked_formats.push_back(format);
      }
    }
  }
}

void check_output_targets(const OutputOptions& o) {
  std::vector<OutputTarget> targets = {{"--json", o.json, false},
                                       {"--csv", o.csv, false},
                                       {"--xlsx", o.xlsx, false},
                                       {"--plot", o.plot, true}};
  const std::vector<OutputTarget> gtfs = gtfs_targets(o);
  targets.insert(targets.end(), gtfs.begin(), gtfs.end());  // no GTFS file is another's path
  check_output_targets(targets);
  if (data::is_stdout_path(o.xlsx)) {
    throw data::InputError("command line", 0, "--xlsx", "a file (XLSX is not written to '-')");
  }
}

nlohmann::json run_provenance(const Problem& problem, const ProblemOptions& options,
                              const nlohmann::json& extra_options) {
  output::RunInputs inputs;
  if (!options.line_path.empty()) inputs.line = options.line_path;
  if (!options.train_path.empty()) inputs.train = options.train_path;
  inputs.from = options.from;
  inputs.to = options.to;
  inputs.objective = options.objective;
  inputs.ds_m = options.ds_m;
  inputs.dv_kmh = options.dv_kmh;
  return output::run_provenance_json(problem.line, problem.train, inputs, extra_options);
}

void write_outputs(const OutputOptions& o, const nlohmann::json& report,
                   const output::Timeline& timeline, const std::string& title,
                   const output::SummaryRows& summary, const physics::Trip* trip,
                   const data::Line* line) {
  data::OutputBatch batch;
  if (!o.gtfs.empty()) {
    if (!trip || !line) throw std::logic_error("--gtfs without a trip and line to write");
    add_gtfs_outputs(batch, o, {{"ecorail-1", *trip}}, *line);
  }
  if (!o.json.empty()) {
    batch.add(o.json, [&](std::ostream& out) { output::write_json(out, report); });
  }
  if (!o.csv.empty() || !o.xlsx.empty()) {
    const output::Timeline rows = output::per_second(timeline);
    if (!o.csv.empty()) {
      batch.add(o.csv, [&](std::ostream& out) { output::write_profile_csv(out, rows); });
    }
    if (!o.xlsx.empty()) {
      batch.add_produced(o.xlsx, [&](const std::filesystem::path& tmp) {
        output::write_profile_xlsx_file(tmp, rows, summary);
      });
    }
  }
  if (!o.plot.empty()) {
    const auto format = output::plot_format_for(o.plot);
    if (!format) throw std::runtime_error("cannot write " + o.plot + ": not .svg or .png");
    const auto labels = plot_labels(o, report);
    batch.add_produced(o.plot, [&](const std::filesystem::path& tmp) {
      output::write_speed_plot_file(tmp, timeline, title, labels, *format);
    });
  }
  batch.commit();
}

}  // namespace ecorail::cli
