// A start for the headway search from the maximisers of a Lagrangian relaxation of the span
// (energy::FleetEnergyModel::relaxation_maximisers_s; for the power-flow model the window
// bound's DP in the core, one headway sequence per multiplier tried). Each maximiser is the best
// sequence at its price of time, but their sums miss the span, some above it and some below. Two of
// them on either side are joined, a prefix of one to the suffix of the other, where the joined sum
// comes nearest the span (the window terms of the relaxation then change only at the join), and the
// few seconds still missing are spread one at a time over the headways, evenly along the day,
// within the headway limits. Without a peak window only (one headway class); the annealing and
// polish that follow price the junction and the spread seconds.
#pragma once

#include <vector>

#include "fleet/fleet_problem.hpp"

namespace ecorail::fleet {

// Headways (trains - 1 of them, within [headway_min_s, headway_max_s], summing to span_s) joined
// from the maximisers as above; empty when none has the problem's number of headways.
std::vector<int> relaxed_start_headways(const std::vector<std::vector<int>>& maximisers_s,
                                        const FleetProblem& problem);

// Every join of two maximisers (a prefix of one, the suffix of the other, both orders, each at
// the point nearest the span) that misses the span by at most a second a headway, closed as
// above, without repeats; the nearest join alone when none does. The relaxation's value of a
// join is not its used energy (the maximiser nearest the span is not always the best part), so
// the search prices them and starts from the best: on question 2.1 the nearest join used
// 5 726 784.8 kJ and the best 5 785 582.7 kJ (docs/fleet.md).
std::vector<std::vector<int>> relaxed_start_candidates(
    const std::vector<std::vector<int>>& maximisers_s, const FleetProblem& problem);

// Closes span_s - sum(h) by one-second steps spread evenly over h within [lo_s, hi_s]; false
// when the limits cannot hold the span (h is then unchanged).
bool spread_to_span(std::vector<int>& headways_s, int span_s, int lo_s, int hi_s);

}  // namespace ecorail::fleet
