// Pattern optimisation: dwells and section running times chosen jointly with the headways. With
// no timetable coupling every dwell goes to its minimum (dp/journey.hpp, free dwells); with
// regenerated energy shared between trains a longer dwell or a re-timed section can move a
// braking phase onto another train's acceleration. The search alternates: headways optimised
// for the pattern (optimise_headways), then the pattern improved for those headways by moves
// that keep the trip time (a dwell longer by delta and the section before or after it shorter by
// delta, or the reverse; delta moved between two neighbouring sections; deltas 4, 2, 1 s), each
// section re-solved energy-optimally for its new running time on the section library (solves are
// cached), the first improving move taken, until no move improves; then the headways once more.
// With per-train patterns (power-flow and sections models) a last stage gives every train its
// own pattern: for each train in turn all its moves are priced at once against the fleet laid
// out in one power balance (energy::FleetBalance::substation_change_if, in parallel) and the best
// improving one is taken, sweep after sweep until none improves. Every pattern the search keeps
// is feasible (dwells in range, each running time above its section's flat-out run) and the
// result is never worse than the headways alone (the search only accepts improvements).
// The network model (--model network) prices a candidate pattern first on the annealing's coarse
// grid (anneal_step_s: one load flow per second of the day, NetworkBalance) and only a
// candidate that is better there is evaluated on the model's own grid, where it must improve to
// be taken; per-train patterns are not built for it (its balance lays one trip under every
// train).
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "dp/section_library.hpp"
#include "fleet/fleet_pattern.hpp"
#include "fleet/headway_optimiser.hpp"

namespace ecorail::fleet {

struct PatternProgress {
  std::string stage;  // "pattern" (one for all) or "per-train"
  int moves_accepted = 0;
  int patterns_evaluated = 0;
  double substation_J = 0.0;
  double elapsed_s = 0.0;
};

struct PatternSearchOptions {
  HeadwayOptimiserOptions headways;
  std::vector<double> deltas_s = {4.0, 2.0, 1.0};
  int max_moves = 200;              // accepted moves of the one-pattern stage at most
  int max_per_train_moves = 5000;   // accepted moves of the per-train stage at most
  bool per_train_patterns = false;  // power-flow and sections models only
  // headways.time_limit_s is the limit of the whole search, every stage and the final
  // evaluations included (0: none): the first headway search may take a third of it and the
  // pattern moves until two thirds, the headways for the pattern found (and the per-train
  // stage) the rest. headways.threads also prices the per-train moves (0: OpenMP's default).
  std::function<void(const PatternProgress&)> progress;
  bool IsValid(std::string* error) const;
};

struct PatternSearchResult {
  PatternTrip pattern;               // the pattern for all trains and its trip
  HeadwayOptimiserResult timetable;  // headways and the final evaluation
  FleetEvaluation headways_only;     // the start: default pattern, its optimal headways
  FleetEvaluation common_pattern;    // one pattern for all, before any per-train stage
  int moves_accepted = 0;
  int patterns_evaluated = 0;
  // Candidates evaluated in full for the whole fleet (overlap and network models; the network
  // model evaluates in full only those its coarse screen finds better).
  int full_evaluations = 0;
  // Per-train stage (empty when not asked): each train's pattern and trip (departing at 0).
  std::vector<FleetPattern> per_train;
  std::vector<physics::Trip> per_train_trips;
  int per_train_moves_accepted = 0;
  int per_train_candidates = 0;
  // Why the last stage stopped: no move improves (a local optimum), or a limit.
  bool time_limit_reached = false;
  bool move_limit_reached = false;
  double wall_s = 0.0;
  // How the whole search ended: its final headway search's termination, settled with the
  // pattern stages' limits (a stage stopped by the time or move limit is never CONVERGENCE).
  Termination termination() const { return timetable.summary.termination; }
  std::string BriefReport() const;
  // The brief report, then the final headway search's full report (gap, bound, limits).
  std::string FullReport() const;
};

// The regenerated energy a fleet used: for the network model the energy that entered the line
// (FleetEnergy's used is traction less substation energy there).
double used_regen_of(const FleetEvaluation& evaluation);

// The model options name the energy model (energy/model_registry.hpp).
PatternSearchResult optimise_pattern(const dp::SectionLibrary& library, const FleetProblem& problem,
                                     const energy::EnergyModelOptions& model,
                                     const PatternTrip& start, const PatternSearchOptions& options);

// The registered model the options name, for this trip and the problem's fleet.
std::unique_ptr<energy::FleetEnergyModel> make_model(const physics::Trip& trip,
                                                     const FleetProblem& problem,
                                                     const energy::EnergyModelOptions& options);

}  // namespace ecorail::fleet
