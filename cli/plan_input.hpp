// Reading a timetable plan for the delay commands (`ecorail delay`, `ecorail montecarlo`): the
// timetable CSV that `ecorail timetable evaluate|optimise --csv` writes (columns train,
// station, arrival_s, departure_s; others ignored), rows grouped by train, stations in the order
// of their rows; or the 2.1 reference plan. Bad files are data::InputError naming file, row and
// field.
#pragma once

#include <CLI/CLI.hpp>
#include <filesystem>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "cli/problem_options.hpp"
#include "cli/progress_line.hpp"
#include "data/line.hpp"
#include "dp/section_library.hpp"
#include "recovery/plan.hpp"

namespace ecorail::cli {

recovery::Plan read_plan(const std::string& file);
// InputError unless the plan's stations are every station of the line between its first and
// last, in the order of travel.
void check_plan_stations(const data::Line& line, const recovery::Plan& plan,
                         const std::string& file);

// What a delay command runs on: the plan and its stations. From plan_file (read and checked
// against the line, so a bad file fails before any engine is built), or with reference the
// line's stations, the plan itself made on the library afterwards (reference_plan_on).
struct PlanStops {
  recovery::Plan plan;
  std::vector<std::string> stops;
};
PlanStops read_plan_stops(const data::Line& line, bool reference, const std::string& plan_file);

// The section library of the plan's stations for the delay commands: the grid of the problem
// options, frontiers frontier_span_s long, keyed for the frontier cache by line, train and
// curve formula (the same key for `delay` and `montecarlo`, so they share cached frontiers).
std::unique_ptr<dp::SectionLibrary> plan_library(const Problem& p, const ProblemOptions& o,
                                                 const std::vector<std::string>& stops,
                                                 double frontier_span_s);
// The 2.1 reference plan made on that library (docs/delays.md).
recovery::Plan reference_plan_on(const dp::SectionLibrary& library,
                                 const std::vector<std::string>& stops);
// The flags the delay commands share: --plan / --reference (where the plan comes from), and the
// line, train file, grid, threads, frontier span and frontier cache (--frontier-span, --line,
// --train-file, --ds, --dv, --threads, --cache-dir, --no-cache).
void add_plan_source_options(CLI::App* cmd, std::string& plan_file, bool& reference);
void add_plan_engine_options(CLI::App* cmd, ProblemOptions& problem, double& frontier_span_s,
                             std::string& cache_dir, bool& no_cache);
// Progress of the delay commands: the progress line on a terminal (cli/progress_line.hpp) and, off
// a terminal, one line per stage on stderr ("ecorail delay: followers"), so that a log shows where
// a long run is; nothing with --quiet.
class StageProgress {
 public:
  StageProgress(std::string label, bool quiet);
  void update(const char* stage, int done, int total);
  dp::ProgressFn callback();

 private:
  Progress line_;
  std::string label_;
  bool lines_;
  std::string last_stage_;
  std::mutex mutex_;
};

// --cache-dir, or the frontier cache's default directory when it is empty.
std::filesystem::path cache_directory(const std::string& cache_dir);

}  // namespace ecorail::cli
