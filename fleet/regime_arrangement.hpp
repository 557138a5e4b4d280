// The order of the regimes within each stretch of a start built from periodic regimes
// (fleet/regime_start.hpp). The regime DP values every block at its steady state, so it is
// indifferent to where in a stretch (a run of headways of one class between two peak windows or a
// window and an end of the day) each regime's run goes; the junctions between runs are not steady
// and cost used energy, differently by where they fall (on the 2.2 reference day, the run of 300 s
// headways the DP puts in the middle of the long off-peak stretch uses 69 MJ more when it follows
// the morning peak instead: one junction instead of two). This local search prices the orders by
// the model itself: it moves one run to another place in its stretch, or swaps the two headways
// of an alternating run (a, b, a, b -> b, a, b, a), evaluates every such candidate of every
// stretch, and keeps the best while it gains. A stretch keeps its span and its number of
// headways, so every candidate keeps the problem's windows (checked all the same).
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "energy/fleet_energy_model.hpp"
#include "fleet/fleet_problem.hpp"

namespace ecorail::fleet {

struct RegimeArrangementOptions {
  int max_rounds = 8;  // rounds of (price every candidate, keep the best)
  int threads = 0;     // 0: OpenMP's default
  // Asked before each round; true ends the search with the best order so far.
  std::function<bool()> stop;
  bool IsValid(std::string* why) const;
};

struct RegimeArrangement {
  std::vector<int> headways_s;      // the start reordered (the given one when nothing gained)
  std::vector<int> run_of_headway;  // the labels, reordered with it
  double start_used_J = 0.0;        // the model's used energy of the given start
  double used_J = 0.0;              // and of the result (>= start_used_J)
  int rounds = 0;                   // rounds that gained
  long evaluations = 0;             // timetables priced
};

// `run_of_headway[k]` labels headway k's regime (equal labels next to each other form one run;
// an alternating pair's two headways share a label). Headways of different classes are never
// in one stretch; a run that crosses a class boundary is cut there.
RegimeArrangement arrange_regime_runs(const energy::FleetEnergyModel& model,
                                      const FleetProblem& problem,
                                      const std::vector<int>& headways_s,
                                      const std::vector<int>& run_of_headway,
                                      const RegimeArrangementOptions& options = {});

}  // namespace ecorail::fleet
