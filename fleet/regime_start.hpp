// A start for the headway search built from the trip's periodic regimes
// (fleet/periodic_regimes.hpp): every headway class (peak, off-peak) is analysed on a coarse
// grid and its best regimes refined to whole seconds (resonances are sharper than the grid);
// then a DP over (headways so far, clock time) fills the span with blocks:
// single headways valued by their constant regime, and alternating pairs of the best resonant
// regimes of each class (those worth more than their two constants side by side) valued by their
// pair regime. Peak windows are thus filled with as many trains as their best peak regime makes
// worth, and each off-peak stretch with the mixture of regimes that fits its length and count
// best. Junctions between regimes are not valued by the DP; where in its stretch each regime's
// run goes is then chosen by pricing the orders with the model (fleet/regime_arrangement.hpp).
#pragma once

#include <functional>
#include <vector>

#include "energy/fleet_energy_model.hpp"
#include "fleet/fleet_problem.hpp"
#include "fleet/periodic_regimes.hpp"

namespace ecorail::fleet {

struct RegimeStart {
  std::vector<int> departures_s;              // empty when no timetable fits or `stop` ended it
  int grid_s = 0;                             // the grid of the (off-peak) analysis
  std::vector<PeriodicRegime> offpeak, peak;  // the analyses (peak empty without windows)
  double predicted_used_J = 0.0;              // the DP's value (junctions not priced)
  // The regime of each headway (an alternating pair's two headways share one label).
  std::vector<int> regime_of_headway;
  // build_regime_start: the model's used energy of the DP's timetable, and of the runs
  // reordered within their stretches (the start returned); evaluations of that reordering.
  double dp_used_J = 0.0, arranged_used_J = 0.0;
  long arrangement_evaluations = 0;
};

// The grid of one class's analysis (headways lo_s..hi_s): 10 s, or half the range when that is
// below 10 s (at least 1 s). The span and the windows' edges may lie anywhere.
int regime_grid_s(int lo_s, int hi_s);

// The DP alone, on given analyses (sorted as analyse_periodic_regimes returns them); at most
// `pairs_per_class` alternating pairs of each class become blocks. `stop` (may be empty) is
// asked once a layer: true gives no start.
RegimeStart regime_start_from(const FleetProblem& problem, int grid_s,
                              std::vector<PeriodicRegime> offpeak, std::vector<PeriodicRegime> peak,
                              int pairs_per_class = 16, const std::function<bool()>& stop = {});

// The `top` best regimes (by used energy per headway) each refined by hill climbing over whole
// seconds within [lo_s, hi_s], added to the list with the constants of each refined pair; a
// climb ends early once `stop` (may be empty) returns true.
std::vector<PeriodicRegime> refine_regimes(const energy::FleetEnergyModel& model,
                                           std::vector<PeriodicRegime> regimes, int lo_s, int hi_s,
                                           int top, int threads,
                                           const std::function<bool()>& stop = {});

// Analyses on the grid, the best regimes refined to whole seconds, the DP by whole seconds, and
// the runs of its regimes reordered within their stretches; the model is the one the search
// anneals on.
// `arrange_on` prices the reordering (the model of the result; `model` when null). `stop` (may
// be empty) is asked between regimes and stages: true before the DP gives no start, after it
// ends the reordering with its best so far.
RegimeStart build_regime_start(const energy::FleetEnergyModel& model, const FleetProblem& problem,
                               int threads, const energy::FleetEnergyModel* arrange_on = nullptr,
                               const std::function<bool()>& stop = {});

}  // namespace ecorail::fleet
