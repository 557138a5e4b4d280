// Headway optimisation: the departures that minimise the fleet's substation energy (maximise the
// regenerated energy used) for one pattern and any energy model (energy/fleet_energy_model.hpp),
// written once against the model's interface.
//   A model whose used energy decomposes over headways (the overlap models): solved exactly by
//     the separable DP (train ahead) or the chain DP (either neighbour), headway_dp.hpp, and
//     with peak classes by the windowed DPs (windowed_dp.hpp).
//   Any model with an incremental balance (power-flow, sections, network): starts from the
//     maximisers of the model's bound relaxation joined to the span (relaxed_start.hpp), the
//     exact optimum of the two-train approximation (every headway valued by what two trains that
//     far apart alone are worth) and from the uniform timetable, runs simulated annealing from
//     each start and restart on the coarser grid of anneal_step_s (OpenMP over the runs; random
//     numbers from a counter-based generator keyed by seed, run and move, so results do not
//     depend on the thread count), then polishes (every train tried at every departure within a
//     window until no move helps) on the grids of the model's search plan. The model's lower
//     bound certifies the result: the summary reports the bound and the gap.
// Termination: CONVERGENCE when the proven gap is within gap_fraction of the substation energy
// (an exact DP proves a gap of 0); a search stopped by its time limit or its move budget with a
// larger gap is NO_CONVERGENCE (a feasible, usable timetable; the gap says how far from the
// optimum it may be); FAILURE when the model found no solution for the result. A time limit is
// one for the whole search: the annealing takes the model's share of it, the polish the rest.
#pragma once

#include <cstdint>
#include <functional>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "dp/termination.hpp"
#include "energy/fleet_energy_model.hpp"
#include "fleet/fleet_problem.hpp"

namespace ecorail::fleet {

using dp::Termination;
using dp::termination_name;
using energy::FleetEnergy;
using energy::FleetEvaluation;

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
  // Step of the annealing's balance (s, divides 1 s; the model's step if that is coarser); the
  // polish then works on the grids of the model's search plan.
  double anneal_step_s = 1.0;
  double time_limit_s = 0.0;  // of the whole search; 0: none
  // CONVERGENCE only when (bound - result) / substation energy is at most this.
  double gap_fraction = 1e-4;
  int threads = 0;  // 0: OpenMP's default
  // Anytime rounds after the first (two runs each: the best so far re-annealed from
  // reanneal_temperature times the start temperature, and a start annealed with new draws):
  // with a time limit as many as fit (a round the limit cuts short is dropped), else `rounds`.
  int rounds = 0;
  double reanneal_temperature = 0.1;
  // A start from the trip's periodic regimes (regime_start.hpp), with peak windows or without.
  bool regime_start = true;
  // Without peak windows, a start joined from the maximisers of the model's bound relaxation
  // (relaxed_start.hpp), when its bound has them.
  bool relaxed_start = true;
  // With peak windows the annealing also shifts blocks of consecutive trains (classes kept).
  bool block_moves = true;
  // Without peak windows, each round's best goes through the model's exact search near it
  // (FleetEnergyModel::refined_headways_s) and the polish on the model's grid again, while
  // either gains.
  bool exact_refine = true;
  // With a time limit and without peak windows, after the first round: the model's exact
  // search on part of the domain (FleetEnergyModel::exact_part_optimum; the power-flow model:
  // every headway in the core) within the time left; its optimum replaces the result when
  // better, and the summary names the part no timetable of which is better.
  bool exact_part = true;
  // The caller's own timetables (departures, each keeping the problem), also starts: each is
  // annealed from reanneal_temperature (it keeps its structure) and polished, and the result
  // never uses less than the best of them on the model's grid. A model solved exactly (the
  // overlap models) needs none: its optimum is never worse.
  std::vector<std::vector<int>> given_starts_s;
  std::function<void(const OptimiserProgress&)> progress;
  bool IsValid(std::string* error) const;
};

struct HeadwayOptimiserSummary {
  Termination termination = Termination::FAILURE;
  std::string method;
  bool exact = false;  // the optimum is proven (exact DP)
  double used_regen_J = 0.0;
  double substation_J = 0.0;
  double bound_used_regen_J = 0.0;  // NaN when the bound is on the substation energy
  double gap_fraction = 0.0;        // the proven gap, a fraction of the substation energy
  // Network model (energy/network_bound.hpp): a lower bound on substation + curtailed traction
  // energy of every timetable, NaN for the other models; gap_fraction is then (substation +
  // curtailed traction - bound) / substation energy.
  double bound_substation_J = std::numeric_limits<double>::quiet_NaN();
  double curtailed_traction_J = 0.0;
  double start_used_J = 0.0;  // best start before annealing and polish
  // The best of HeadwayOptimiserOptions::given_starts_s on the model's grid (NaN: none given,
  // or a model solved exactly); the result never uses less.
  double given_start_used_J = std::numeric_limits<double>::quiet_NaN();
  // Pair sum of the result (energy/pair_bound.hpp): no bound built on pairs of trains can come
  // below it, so (pair sum - used) / substation is the part of the gap such a bound cannot close.
  double pair_sum_J = 0.0;
  long moves = 0;
  long dp_states = 0;
  int rounds = 0;       // anytime rounds completed after the first
  int refinements = 0;  // exact refinements (and polishes after them) that gained
  // When the model's exact search on part of the domain ran to its end: which part
  // (e.g. "every headway in 522-660 s") and its optimum; no timetable of that part uses more.
  std::string exact_part;
  double exact_part_used_J = 0.0;
  double wall_s = 0.0;
  bool time_limit_reached = false;
  std::string message;
  // A timetable to use (dp/termination.hpp's rule): converged, or stopped by a budget with
  // every limit kept and its gap stated.
  bool IsSolutionUsable() const {
    return dp::is_usable(termination, /*budget_stop_keeps_constraints=*/true);
  }
  std::string BriefReport() const;
  std::string FullReport() const;
};

struct HeadwayOptimiserResult {
  std::vector<int> headways_s;
  FleetEvaluation evaluation;
  HeadwayOptimiserSummary summary;
};

// The model must be built for this problem's fleet (limits_of(problem)).
HeadwayOptimiserResult optimise_headways(const energy::FleetEnergyModel& model,
                                         const FleetProblem& problem,
                                         const HeadwayOptimiserOptions& options);

// Sets termination and message from the gap, the stops and the gap tolerance (also after a
// caller replaced the result, e.g. the pattern search keeping its departures).
void settle_termination(HeadwayOptimiserSummary& summary, double gap_tolerance, bool unsolved);

}  // namespace ecorail::fleet
