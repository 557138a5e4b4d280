// A Monte Carlo run from its simulator to what it reports (question 3.2): the days [first, last)
// simulated by recovery::MonteCarlo, the plan without delays, the run's config (everything that
// shapes the days, so shards of one run are recognised as such), and its summary with the
// termination the run reached. `ecorail montecarlo` and ecorail.montecarlo both run through
// here, so their JSON is one document. Also what the run's outputs read off the statistics:
// and the JSON of a plan adjustment (punctuality per station: recovery/monte_carlo_stats.hpp).
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "recovery/monte_carlo.hpp"
#include "recovery/monte_carlo_stats.hpp"
#include "recovery/plan_adjustment.hpp"
#include "recovery/section_runs.hpp"

namespace ecorail::recovery {

// The policy of a name recovery_policy_name gives ("exact", "exact-punctual", "rule"), or none.
std::optional<RecoveryPolicy> recovery_policy_from_name(const std::string& name);
// The follower model of a name follower_model_name gives ("driven", "shortcut"), or none.
std::optional<FollowerModel> follower_model_from_name(const std::string& name);

// What shapes the days beside the simulator's options, for the run's config.
struct MonteCarloRunInfo {
  std::string plan_name = "reference";  // "reference" or the plan file's name
  std::uint64_t days_total = 0;         // days of the whole run (every shard)
  double frontier_span_s = 60.0;        // of the section library's frontiers
  double ds_m = 5.0, dv_kmh = 0.2;      // its grid
  std::uint64_t line_checksum = 0, train_checksum = 0;
};

// The run's "config": plan, trains, days, seed, the delay distribution and every option.
nlohmann::json monte_carlo_config(const MonteCarlo& mc, const MonteCarloRunInfo& info);

struct MonteCarloDays {
  MonteCarloRun run;
  MonteCarloSummary summary;
};

// Days [first, last) of mc on `threads` OpenMP threads (0: all), progress as run_days. The
// summary's termination: CONVERGENCE when every day of [first, last) was simulated and its
// statistics are finite, FAILURE otherwise (no day is left out by a budget: a run is never
// stopped early). wall_s counts from wall_start.
MonteCarloDays simulate_days(
    const MonteCarlo& mc, const SectionRuns& runs, std::uint64_t first, std::uint64_t last,
    int threads, const MonteCarloRunInfo& info, const std::function<void(int, int)>& progress = {},
    std::chrono::steady_clock::time_point wall_start = std::chrono::steady_clock::now());

// The summary of a whole run read back or merged from shards (days 0 .. days - 1), with the
// same termination rule.
MonteCarloSummary run_summary(const MonteCarloRun& run);

// The JSON of `montecarlo --adjust` (docs/outputs.md): every candidate's pattern, plan energy
// and statistics, the chosen one and the brief report.
nlohmann::json plan_adjustment_json(const PlanAdjustmentResult& r, const std::string& plan_name,
                                    std::int64_t seed, std::int64_t search_days);

}  // namespace ecorail::recovery
