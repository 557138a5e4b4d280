// The flags of `ecorail montecarlo` and what they parse into: the simulator's options, the shard
// of the days to run, the plan adjustment's options; each refused value is one error naming its
// flag (exit 2), before any work.
#pragma once

#include <CLI/CLI.hpp>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "cli/problem_options.hpp"
#include "recovery/monte_carlo.hpp"
#include "recovery/plan_adjustment.hpp"

namespace ecorail::cli {

struct MonteCarloArgs {
  ProblemOptions problem;  // --line, --train-file, --ds, --dv, --threads
  std::string plan_file;
  bool reference = false;
  long long days = 1000;
  long long seed = 1;
  std::string recovery = "exact";
  std::string followers = "driven";
  std::string tail = "exponential:30";
  // --early, --run-early, --min-dwell, --takeover, --punctual, --separation, --knot-step and
  // --step set these fields of the simulator's options (and take their defaults from them);
  // simulation_options completes them.
  recovery::MonteCarloOptions sim;
  std::string run_early_values = "0";
  double frontier_span_s = 60.0;
  std::string shard;
  std::string cache_dir;
  bool no_cache = false, quiet = false, full_report = false;
  std::string json, csv, svg_prefix;
  // Plan adjustment.
  bool adjust = false;
  double target = 0.97;
  long long search_days = 200;
  std::string thetas = "0,0.25,0.5,0.75,1", extra_dwells = "0,3";
  std::string adjusted_csv;
  // merge
  std::vector<std::string> merge_files;
};

// Every flag of a run (the merge subcommand adds its own).
void add_montecarlo_options(CLI::App* cmd, MonteCarloArgs& a);
// --days, --seed, --recovery, --tail and the simulator's flags, checked (IsValid).
recovery::MonteCarloOptions simulation_options(const MonteCarloArgs& a);
// --shard as (i, N); (1, 1) without it.
std::pair<int, int> shard_of(const MonteCarloArgs& a);
// The --adjust flags (defaults when --adjust is not given, which refuses --adjusted-csv).
recovery::PlanAdjustmentOptions adjustment_options(const MonteCarloArgs& a);
// Refuses a run whose day records would not fit in memory, before anything is allocated.
void check_day_memory(std::uint64_t days, std::size_t stations);

}  // namespace ecorail::cli
