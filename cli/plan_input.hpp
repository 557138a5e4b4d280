// The flags and the progress line the delay commands (`ecorail delay`, `ecorail montecarlo`)
// share: where the plan comes from (--plan, a timetable CSV read by recovery/plan_source.hpp, or
// --reference), the engine and frontier-cache flags, and the section library of the problem
// options.
#pragma once

#include <CLI/CLI.hpp>
#include <filesystem>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "cli/problem_options.hpp"
#include "cli/progress_line.hpp"
#include "dp/section_library.hpp"
#include "recovery/plan_source.hpp"

namespace ecorail::cli {

// The section library of the plan's stations for the delay commands: the grid of the problem
// options, frontiers frontier_span_s long (recovery::plan_section_library).
std::unique_ptr<dp::SectionLibrary> plan_library(const Problem& p, const ProblemOptions& o,
                                                 const std::vector<std::string>& stops,
                                                 double frontier_span_s);
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
