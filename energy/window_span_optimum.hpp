// The exact optimum of the power-flow model (one supply section) over every timetable whose
// headways all lie in a range inside the core (energy/window_terms.hpp: at least L / 4, so at
// most four trains share the line), with the span kept exactly. On the core the used energy is a
// sum of window terms of three consecutive headways on the model's own grid, so a DP whose state
// is (last two headways, sum so far) is exact; it is made affordable by a Lagrangian bound:
//  1. the multiplier mu of the span is set where the relaxed DP (the sum priced, not kept) is
//     least (bisection on the maximiser's sum, its subgradient), which gives L(mu), an upper
//     bound on every timetable of the range, and for each (position, last two headways) the best
//     relaxed value before and after it;
//  2. the exact DP then drops every state whose value so far plus the best relaxed value after
//     it (the rest of the sum priced at mu) is below the incumbent (a given timetable's value):
//     no timetable through it can beat the incumbent, by weak duality.
// So the result is the best timetable of the range, or the incumbent when none beats it, with
// L(mu) beside it. No other restriction: the partial sums range over all the span allows (the
// bound keeps the DP small; on question 2.1's core 95 % of the (position, pair) states go before
// the exact DP, docs/fleet.md). It is not a certificate for the whole problem, whose timetables
// may have headways below the core (energy/window_bound.hpp bounds those).
#pragma once

#include <string>
#include <vector>

#include "energy/model_options.hpp"
#include "energy/power_flow_profile.hpp"

namespace ecorail::energy {

struct WindowSpanOptions {
  int lowest_headway_s = 0;       // the range's least headway; 0: the core's least (L / 4)
  int max_dual_evaluations = 40;  // relaxed DP runs of the multiplier bisection
  int threads = 0;                // 0: OpenMP's default
  // 0: none. Checked between the window terms' rows, the multiplier's DP runs and the exact DP's
  // positions; the terms' cost is projected from their first rows, and the search gives up at
  // once when they alone would take more than 60 % of the limit.
  double time_limit_s = 0.0;
  bool IsValid(std::string* error) const;
};

struct WindowSpanSummary {
  bool applicable = false;
  std::string why_not;  // also when the time limit stopped it (time_limit_reached)
  bool time_limit_reached = false;
  // The search ran to its end: the result is the range's optimum (or the incumbent is).
  bool complete() const { return applicable && !time_limit_reached; }
  int lowest_headway_s = 0, highest_headway_s = 0;  // the range searched
  std::vector<int>
      headways_s;         // the best timetable of the range (the incumbent when none beats it)
  double used_J = 0.0;    // its used regenerated energy on the model's grid
  bool improved = false;  // better than the incumbent
  double incumbent_used_J = 0.0;
  double dual_bound_J = 0.0;  // L(mu): no timetable of the range uses more
  double mu_J_per_s = 0.0;
  int dual_evaluations = 0;
  long window_terms = 0;  // W terms computed
  long exact_states = 0;  // (position, two headways, partial sum) states kept by the exact DP
  long pruned_pairs = 0;  // (position, two headways) dropped by the bound before the exact DP
  double terms_s = 0.0, wall_s = 0.0;
  std::string BriefReport() const;
};

// incumbent_s: a timetable of the problem (any headways; its value counts only when they all lie
// in the range and sum to the span, else the incumbent is minus infinity and nothing is pruned
// by it).
WindowSpanSummary window_span_optimum(const PowerProfile& profile, const FleetLimits& limits,
                                      const std::vector<int>& incumbent_s,
                                      const WindowSpanOptions& options = {});

}  // namespace ecorail::energy
