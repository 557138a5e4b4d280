#include "cli/plan_input.hpp"

#include <cstdio>

#include <cmath>
#include <map>

#include "cli/errors.hpp"
#include "cli/output_options.hpp"
#include "data/csv_reader.hpp"
#include "data/input_error.hpp"
#include "data/route_builder.hpp"
#include "data/train_io.hpp"
#include "output/frontier_cache.hpp"

namespace ecorail::cli {

// The timetable CSV of `ecorail timetable ... --csv` (columns train, station, arrival_s,
// departure_s; others ignored): rows grouped by train, stations in the order of their rows.
recovery::Plan read_plan(const std::string& file) {
  const data::CsvTable table = data::CsvTable::read(file);
  const std::size_t c_train = table.column("train"), c_station = table.column("station");
  const std::size_t c_arr = table.column("arrival_s"), c_dep = table.column("departure_s");
  std::map<long, std::vector<const data::CsvRow*>> by_train;
  for (const data::CsvRow& row : table.rows()) {
    const double k = table.number(row, c_train);
    if (k != std::floor(k) || k < 1 || k > 1e6)
      throw data::InputError(file, row.row, "train", "a train number >= 1");
    by_train[static_cast<long>(k)].push_back(&row);
  }
  if (by_train.empty()) throw data::InputError(file, 0, "train", "at least one train's rows");
  recovery::Plan plan;
  long expected = 1;
  for (const auto& [k, rows] : by_train) {
    if (k != expected)
      throw data::InputError(file, rows.front()->row, "train",
                             "trains numbered 1, 2, ... without gaps; train " +
                                 std::to_string(expected) + " is missing");
    ++expected;
    recovery::TrainStops t;
    std::vector<std::string> names;
    for (const data::CsvRow* row : rows) {
      names.push_back(table.text(*row, c_station));
      t.arrival_s.push_back(table.number(*row, c_arr));
      t.departure_s.push_back(table.number(*row, c_dep));
    }
    if (plan.stations.empty()) plan.stations = names;
    if (names != plan.stations)
      throw data::InputError(file, rows.front()->row, "station",
                             "the same stations for every train (train " + std::to_string(k) +
                                 " differs from train 1)");
    plan.trains.push_back(std::move(t));
  }
  if (const std::string why = plan.problem(); !why.empty())
    throw data::InputError(file, 0, "arrival_s/departure_s", "a timetable that holds: " + why);
  return plan;
}

void check_plan_stations(const data::Line& line, const recovery::Plan& plan,
                         const std::string& file) {
  const std::vector<std::string>& stops = plan.stations;
  std::vector<std::string> line_stops;
  try {
    line_stops = data::stops_between(line, stops.front(), stops.back());
  } catch (const data::InputError&) {
    throw data::InputError(file, 0, "station",
                           "stations of the line; got " + stops.front() + " .. " + stops.back());
  }
  if (line_stops != stops)
    throw data::InputError(file, 0, "station",
                           "every station of the line between " + stops.front() + " and " +
                               stops.back() + ", in the order of travel");
}

PlanStops read_plan_stops(const data::Line& line, bool reference, const std::string& plan_file) {
  PlanStops out;
  if (reference) {
    out.stops = data::stops_between(line, line.stations.front().name, line.stations.back().name);
    return out;
  }
  out.plan = read_plan(plan_file);
  out.stops = out.plan.stations;
  check_plan_stations(line, out.plan, plan_file);
  return out;
}

std::unique_ptr<dp::SectionLibrary> plan_library(const Problem& p, const ProblemOptions& o,
                                                 const std::vector<std::string>& stops,
                                                 double frontier_span_s) {
  dp::SectionLibraryOptions options;
  options.engine = engine_options(o);
  options.frontier_span_s = frontier_span_s;
  require_valid(options);
  char key[200];
  std::snprintf(key, sizeof key, "delay|%016llx|%016llx|%s",
                static_cast<unsigned long long>(p.line.checksum()),
                static_cast<unsigned long long>(data::train_checksum(p.train)),
                o.curve_resistance.c_str());
  return std::make_unique<dp::SectionLibrary>(p.train, data::build_routes(p.line, stops, p.train),
                                              options, key);
}

recovery::Plan reference_plan_on(const dp::SectionLibrary& library,
                                 const std::vector<std::string>& stops) {
  dp::JourneyOptions journey;
  journey.engine = library.options().engine;
  journey.measure_marginals = false;
  return recovery::reference_plan(library, stops, journey);
}

std::filesystem::path cache_directory(const std::string& cache_dir) {
  return cache_dir.empty() ? output::FileFrontierStore::default_directory()
                           : std::filesystem::path(cache_dir);
}

void add_plan_source_options(CLI::App* cmd, std::string& plan_file, bool& reference) {
  cmd->add_option("--plan", plan_file,
                  "timetable CSV as `ecorail timetable evaluate|optimise --csv` writes it");
  cmd->add_flag("--reference", reference,
                "the 2.1 plan: 30 s dwells, optimal split of 1726 s, 100 trains uniform over "
                "63900 s");
  input_files(cmd, {"--plan"});
}

void add_plan_engine_options(CLI::App* cmd, ProblemOptions& problem, double& frontier_span_s,
                             std::string& cache_dir, bool& no_cache) {
  cmd->add_option("--frontier-span", frontier_span_s,
                  "each section's frontier covers [T_min, T_min + span] (s)")
      ->capture_default_str();
  cmd->add_option("--line", problem.line_path, "line (default: the embedded reference line)");
  cmd->add_option("--train-file", problem.train_path,
                  "train TOML or TTOBench JSON (default: the reference train)");
  input_files(cmd, {"--line", "--train-file"});
  cmd->add_option("--ds", problem.ds_m, "grid position step in m")->capture_default_str();
  cmd->add_option("--dv", problem.dv_kmh, "grid speed step in km/h")->capture_default_str();
  cmd->add_option("--threads", problem.threads, "OpenMP threads (default: all cores)");
  cmd->add_option("--cache-dir", cache_dir,
                  "frontier cache directory (default: $XDG_CACHE_HOME/ecorail/frontiers)");
  cmd->add_flag("--no-cache", no_cache, "compute every frontier afresh");
}

StageProgress::StageProgress(std::string label, bool quiet)
    : line_(label, quiet),
      label_(std::move(label)),
      lines_(!quiet && !Progress::stderr_is_terminal()) {}

void StageProgress::update(const char* stage, int done, int total) {
  line_.update(stage, done, total);
  if (!lines_) return;
  std::lock_guard<std::mutex> lock(mutex_);
  if (last_stage_ == stage) return;
  last_stage_ = stage;
  std::fprintf(stderr, "%s: %s\n", label_.c_str(), stage);
  std::fflush(stderr);
}

dp::ProgressFn StageProgress::callback() {
  return [this](const char* stage, int done, int total) { update(stage, done, total); };
}

}  // namespace ecorail::cli
