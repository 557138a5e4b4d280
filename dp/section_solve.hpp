// solve_section: the single-section job end to end. Builds the engine for a train and route,
// searches the time price for the requested running time, re-simulates, lists the regimes and
// returns a Summary that reads like Ceres' solver summary (a Termination, IsSolutionUsable,
// BriefReport for one line, FullReport for everything: problem, grid, search, timing, result,
// warnings). Options are checked (IsValid) before any work: std::invalid_argument.
#pragma once

#include <string>
#include <vector>

#include "dp/regimes.hpp"
#include "dp/section_engine.hpp"
#include "dp/termination.hpp"
#include "dp/time_target.hpp"

namespace ecorail::dp {

struct SectionSolveOptions {
  EngineOptions engine;
  TimeSearchOptions search;
  // A minimum length or duration of the control phases (dp/regimes.hpp); none by default.
  MinRegimeOptions min_regime;
  // Checks every field; on failure writes one sentence naming the field into *error.
  bool IsValid(std::string* error) const {
    return engine.IsValid(error) && search.IsValid(error) && min_regime.IsValid(error);
  }
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
  Termination termination = Termination::FAILURE;
  bool converged() const { return termination == Termination::CONVERGENCE; }
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
  // With a minimum regime: the minimum, the phases merged and what it cost (energy by the
  // objective, against the unmerged optimum at the same running time).
  MinRegimeOptions min_regime;
  int merged_regimes = 0;
  double unmerged_energy_kJ = 0.0;
  double min_regime_cost_kJ = 0.0;
  // The cruise polish (dp/cruise_polish.hpp): whether it replaced the grid's run, the short
  // phases it dropped, the re-simulations it spent and what it saved (energy by the objective).
  bool cruise_polished = false;
  int cruise_dropped_phases = 0;
  int cruise_polish_simulations = 0;
  double cruise_polish_saving_kJ = 0.0;
  // Whether the time was searched again with the grid's own cruises (the converged run cost
  // more held than the grid's at its price: dp::kGridCruisesCheckShare), and whether that run,
  // cheaper, was kept and by how much (energy by the objective).
  bool grid_cruises_searched = false;
  bool grid_cruises_kept = false;
  double grid_cruises_saving_kJ = 0.0;
  std::vector<std::string> warnings;

  std::string BriefReport() const;
  std::string FullReport() const;
  // The minimum-regime line of both reports (empty without a minimum).
  std::string min_regime_text() const;
  // False when the run misses its stop or its time: such a run must not be written as a result.
  bool IsSolutionUsable() const { return is_usable(termination); }
};

struct SectionSolution {
  LambdaRun run;
  std::vector<RegimeSpan> regimes;
  SectionSolveSummary summary;
};

SectionSolution solve_section(const physics::Train& train, const physics::Route& route,
                              double target_time_s, const SectionSolveOptions& options);

// What a result must meet (kStopTolerance_m, kTimeTolerance_s: dp/time_target.hpp): it comes
// to rest at the stop and, for a target time, runs within the tolerance of it.
bool run_meets_targets(const physics::SimulationResult& sim, double target_time_s);

// Fills the result part of a summary (energies, time, stop, overspeed, warnings) from a run.
void summarise_run(const physics::SimulationResult& sim, double target_time_s,
                   SectionSolveSummary& summary);

}  // namespace ecorail::dp
