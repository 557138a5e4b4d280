// Headway optimisation: the departures that minimise the fleet's substation energy (maximise
// the regenerated energy used) for one pattern and energy model.
//   overlap, ahead: the used energy is a sum over headways of one function of each headway;
//     solved exactly by the separable DP (headway_dp.hpp).
//   overlap, either: a sum over headways less a non-negative double count of consecutive
//     pairs; solved exactly by the chain DP.
//   power-flow, sections: no decomposition is exact. Starts from the exact optimum of the
//     two-train approximation (every headway valued by what two trains that far apart exchange)
//     and from the uniform timetable, runs simulated annealing from each start and restart with
//     incremental evaluation (OpenMP over the runs; random numbers from a counter-based
//     generator keyed by seed, run and move, so results do not depend on the thread count),
//     then polishes the best deterministically (every train tried at every departure within a
//     window until no move helps). The pair bound (pair_bound.hpp) certifies it: the summary
//     reports the bound and the gap in substation energy.
// The summary reads like a Ceres summary: termination, usable or not, brief and full reports.
#pragma once

#include <cstdint>
#include <functional>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "dp/termination.hpp"
#include "timetable/fleet_models.hpp"

namespace ecorail::timetable {

// How the optimiser ended, named as every solver names it (dp/termination.hpp). A timetable
// found before --time-limit stopped the search is feasible and usable but NO_CONVERGENCE.
using dp::Termination;
using dp::termination_name;

struct OptimiserProgress {
  double elapsed_s = 0.0;
  double best_used_J = 0.0;
  double bound_used_J = 0.0;  // NaN while unknown
  std::string stage;
};

struct HeadwayOptimiserOptions {
  std::uint64_t seed = 1;
  int restarts = 2;              // annealing runs per start
  long moves_per_run = 2000000;  // annealing moves of one run
  int polish_window_s = 20;      // a polish tries departures within +-window of the current
  // Step of the annealing's power balance (s, divides 1 s; the model's step if that is
  // coarser); the polish then works on the model's own step.
  double anneal_step_s = 1.0;
  double time_limit_s = 0.0;  // 0: none; when reached the result is NO_CONVERGENCE
  int threads = 0;            // 0: OpenMP's default
  // Also certify with the window bound (window_bound.hpp; power-flow, one class): valid over
  // every timetable and much tighter than the pair bound, but it costs about a minute of CPU
  // on question 2.1's reference case, so it is asked for.
  bool window_bound = false;
  std::function<void(const OptimiserProgress&)> progress;
  bool IsValid(std::string* error) const;
};

struct HeadwayOptimiserSummary {
  Termination termination = Termination::FAILURE;
  std::string method;
  bool exact = false;  // the optimum is proven (exact DP)
  double used_regen_J = 0.0;
  double substation_J = 0.0;
  double bound_used_regen_J = 0.0;  // NaN when no bound (exact methods: equals used)
  double gap_fraction = 0.0;        // (bound - used) / substation energy
  // Network model (network_bound.hpp): a lower bound on substation + curtailed traction energy
  // of every timetable, NaN for the other models; gap_fraction is then (substation + curtailed
  // traction - bound) / substation energy.
  double bound_substation_J = std::numeric_limits<double>::quiet_NaN();
  double curtailed_traction_J = 0.0;
  double start_used_J = 0.0;  // best start before annealing and polish
  // Pair sum of the result (pair_bound.hpp): no bound built on pairs of trains can come below
  // it, so (pair sum - used) / substation is the part of the gap such a bound cannot close.
  double pair_sum_J = 0.0;
  long moves = 0;
  long dp_states = 0;
  double wall_s = 0.0;
  bool time_limit_reached = false;
  std::string message;
  bool IsSolutionUsable() const { return termination != Termination::FAILURE; }
  std::string BriefReport() const;
  std::string FullReport() const;
};

struct HeadwayOptimiserResult {
  std::vector<int> headways_s;
  FleetEvaluation evaluation;
  HeadwayOptimiserSummary summary;
};

HeadwayOptimiserResult optimise_headways(const FleetModels& models,
                                         const HeadwayOptimiserOptions& options);

}  // namespace ecorail::timetable
