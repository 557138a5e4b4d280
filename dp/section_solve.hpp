// solve_section: the single-section job end to end. Builds the engine for a train and route,
// searches the time price for the requested running time, re-simulates, lists the regimes and
// returns a Summary that reads like Ceres' solver summary (BriefReport for one paragraph,
// FullReport for everything: problem, grid, search, timing, result, warnings).
#pragma once

#include <string>
#include <vector>

#include "dp/regimes.hpp"
#include "dp/section_engine.hpp"
#include "dp/time_target.hpp"

namespace ecorail::dp {

struct SectionSolveOptions {
  EngineOptions engine;
  TimeSearchOptions search;
};

struct SectionSolveSummary {
  std::string from, to;
  double distance_m = 0.0;
  double target_time_s = 0.0;
  double min_time_s = 0.0;
  GridSpec grid;
  int stages = 0;
  int nodes = 0;
  int threads = 1;
  Objective objective = Objective::Traction;
  double lambda_J_per_s = 0.0;
  int lambda_evaluations = 0;
  int trim_simulations = 0;
  double trim_shift_m = 0.0;
  bool converged = false;
  double build_wall_s = 0.0;
  double search_wall_s = 0.0;
  double total_wall_s = 0.0;
  double running_time_s = 0.0;
  double traction_energy_kJ = 0.0;
  double braking_energy_kJ = 0.0;
  double regen_energy_kJ = 0.0;
  double net_energy_kJ = 0.0;
  double stop_error_m = 0.0;
  double max_overspeed_kmh = 0.0;
  std::vector<std::string> warnings;

  std::string BriefReport() const;
  std::string FullReport() const;
  // False when the run misses its stop or its time: such a run must not be written as a result.
  bool IsSolutionUsable() const { return converged; }
};

struct SectionSolution {
  LambdaRun run;
  std::vector<RegimeSpan> regimes;
  SectionSolveSummary summary;
};

SectionSolution solve_section(const physics::Train& train, const physics::Route& route,
                              double target_time_s, const SectionSolveOptions& options);

// What a result must meet: it comes to rest at the stop (within kStopTolerance_m) and, for a
// target time, runs within kTimeTolerance_s of it.
inline constexpr double kStopTolerance_m = 0.5;
inline constexpr double kTimeTolerance_s = 0.1;
bool run_meets_targets(const physics::SimulationResult& sim, double target_time_s);

// Fills the result part of a summary (energies, time, stop, overspeed, warnings) from a run.
void summarise_run(const physics::SimulationResult& sim, double target_time_s,
                   SectionSolveSummary& summary);

}  // namespace ecorail::dp
