// Exact choice of whole-second departures under clock-dependent headway classes (question 2.2,
// windowed_classes.hpp): maximise sum_k value(h_k), where a headway's value may depend on its
// class (peak or off-peak) and the class depends on where the headway sits on the clock. The
// DP's state is (headways so far, clock time of the last departure); only the states from which
// the span can still be reached in the remaining headways (WindowedReach) are visited, and the
// allowed headways from a state are two contiguous ranges (off-peak up to the next window,
// peak overlapping it). It is the separable DP of headway_dp.hpp with the class rule added: the
// overlap model (train ahead), the two-train approximation of power-flow, and the uniform
// timetable (a value of minus the squared deviation from the class mean) are all solved by it.
// A chain version (value of consecutive headway pairs, the overlap model with either
// neighbour) carries the last headway in the state too.
#pragma once

#include <vector>

#include "fleet/fleet_problem.hpp"
#include "fleet/headway_dp.hpp"

namespace ecorail::fleet {

// Values indexed by h - problem.any_headway_min_s(), for h up to problem.any_headway_max_s().
struct WindowedValue {
  std::vector<double> peak, offpeak;
};

// Throws std::invalid_argument when no timetable exists or the tables have the wrong size,
// std::length_error when the state space exceeds max_states.
HeadwayChoice maximise_windowed(const FleetProblem& problem, const WindowedValue& value,
                                long max_states = 200'000'000);

// sum_k value(h_k) - sum_k penalty(h_k, h_{k+1}), penalty[a * m + b] >= 0 for consecutive
// headways any_min + a, any_min + b (m = any_max - any_min + 1). The state also carries the last
// headway; the inner maximum stops as soon as no candidate can win (penalty >= 0). Only the
// states reachable both ways are laid out (one 2-byte back pointer each; values two layers at a
// time); std::length_error when they exceed max_states or half the memory the process can have.
HeadwayChoice maximise_windowed_chain(const FleetProblem& problem, const WindowedValue& value,
                                      const std::vector<double>& penalty,
                                      long max_states = 3'000'000'000);

}  // namespace ecorail::fleet
