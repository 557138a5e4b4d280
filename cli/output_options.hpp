// Output flags shared by the engine commands (--json, --csv, --xlsx, --plot, --plot-x) and the
// writing of them. Every target is checked before any work starts (directory exists and is
// writable, the target is a regular file or absent, no two outputs share a path, a plot is
// .svg or .png and gnuplot can draw it: installed, with the svg or pngcairo terminal); the
// outputs are then written to temporaries and renamed into place together only when all of them
// succeeded, so a failed run leaves none behind. "-" writes an output to standard output.
#pragma once

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "cli/problem_options.hpp"
#include "data/atomic_file.hpp"
#include "data/line.hpp"
#include "output/profile_writers.hpp"
#include "output/timeline.hpp"
#include "physics/trip.hpp"

namespace ecorail::cli {

struct OutputOptions {
  std::string json, csv, xlsx, plot;
  std::string plot_x = "distance";  // distance or time
  // GTFS export (add_gtfs_options; commands that make a timetable): the directory that gets
  // the feed (output/gtfs_writer.hpp), the clock time of t = 0, the agency, the service days.
  std::string gtfs;
  std::string gtfs_start = "00:00:00";
  std::string gtfs_agency, gtfs_agency_url, gtfs_timezone;
  std::string gtfs_lang = "en";
  std::string gtfs_dates;  // FIRST:LAST, YYYYMMDD:YYYYMMDD
  std::string gtfs_weekdays = "mon,tue,wed,thu,fri,sat,sun";
  // What write_outputs reads besides the report: the timeline (profile CSV, XLSX, plot) and the
  // trip (GTFS). A long journey's are built from a trace of a million points, so a command
  // builds them only when asked for.
  bool needs_timeline() const { return !csv.empty() || !xlsx.empty() || !plot.empty(); }
  bool needs_trip() const { return !gtfs.empty(); }
};

// One output of a command, for check_output_targets: its flag, its path (empty: not asked
// for), and whether it is a plot (gnuplot, .svg or .png).
struct OutputTarget {
  std::string flag;
  std::string path;
  bool plot = false;
  bool new_directory = false;  // its directory is made when the outputs are written (--gtfs)
};

void add_output_options(CLI::App* cmd, OutputOptions& o);
// Marks options of cmd as input files: each value given is registered as an input of the run
// when it is parsed (data::register_input), so that check_output_targets, and every output
// written through data::OutputBatch, refuses to replace it. Every command marks its inputs with
// one call; a flag cmd does not have is a programming error (std::logic_error at start-up).
void input_files(CLI::App* cmd, std::initializer_list<const char*> flags);
// --gtfs DIR and --gtfs-start HH:MM:SS (or seconds) for commands whose result is a timetable.
void add_gtfs_options(CLI::App* cmd, OutputOptions& o);
// InputError naming the flag for the first unsuitable target (see the header summary).
void check_output_targets(const std::vector<OutputTarget>& targets);
void check_output_targets(const OutputOptions& o);
// The GTFS files of --gtfs DIR as output targets (none when DIR is empty), after every --gtfs-*
// flag is checked; InputError naming the flag: DIR neither an existing directory nor a new one
// in an existing directory, a missing or malformed agency, time zone or service dates, a
// --gtfs-start that does not parse.
std::vector<OutputTarget> gtfs_targets(const OutputOptions& o);
// --gtfs-start in seconds past midnight: "HH:MM:SS", "HH:MM" or a number of seconds, from 0 to
// below 24 h; InputError naming --gtfs-start otherwise.
double gtfs_start_s(const std::string& text);
// Refuses --gtfs (InputError naming the stations table and the stations) when a station of
// stops has no coordinates; nothing when o.gtfs is empty. Called before the work.
void check_gtfs_stops(const OutputOptions& o, const data::Line& line,
                      const std::vector<std::string>& stops);
// Adds the GTFS feed of o.gtfs to batch (nothing when o.gtfs is empty): trips as given, every
// time shifted by --gtfs-start, stops located by line's coordinates. Makes the directory when
// it is new.
void add_gtfs_outputs(data::OutputBatch& batch, const OutputOptions& o,
                      const std::vector<std::pair<std::string, physics::Trip>>& trips,
                      const data::Line& line);
// The "provenance" of a report (output/provenance.hpp): program, line and train with their
// checksums, grid, and the options that shape the result (--threads is left out: it does not
// change the result, and the report states it under "threads"). extra_options adds the
// command's own (running time, dwells, split...).
nlohmann::json run_provenance(const Problem& problem, const ProblemOptions& options,
                              const nlohmann::json& extra_options = nlohmann::json::object());
// Writes every requested output, all or none. The plot names the stations from the report's
// "stops" (or "from" and "to") and the objective from its "objective" (or its provenance).
// trip: the run as a timetable, and line, its stations' coordinates, for --gtfs (required when
// o.gtfs is set).
void write_outputs(const OutputOptions& o, const nlohmann::json& report,
                   const output::Timeline& timeline, const std::string& title,
                   const output::SummaryRows& summary, const physics::Trip* trip = nullptr,
                   const data::Line* line = nullptr);

}  // namespace ecorail::cli
