// A certificate for the power-flow and sections models (energy/power_flow_model.hpp): an upper
// bound on the regenerated energy any timetable of the problem can use. In a bin, min(sum_i R_i,
// sum_j T_j) <= sum_i sum_j min(R_i, T_j) (min is subadditive in each argument), so the used energy
// is at most the trains' self terms plus, for every pair of trains, P(t_j - t_i): what two trains
// that far apart could exchange if nobody else drew or fed power. The pair sum is then maximised
// over all timetables, relaxed so that it is exact to compute: pairs one and two headways apart are
// counted exactly in a chain over consecutive headways, pairs further apart by the most they
// could exchange given the two headways known, and the fixed sum of headways is priced by a
// Lagrange multiplier mu (every mu gives a valid bound; the best is searched). The bound is
// tight when at most one train feeds one other at a time; when a braking train feeds two
// accelerating ones at once it counts both, which is what limits it.
#pragma once

#include <vector>

#include "energy/model_options.hpp"
#include "energy/power_flow_profile.hpp"

namespace ecorail::energy {

struct PairBound {
  double bound_used_J = 0.0;  // valid upper bound on used regenerated energy
  double self_J = 0.0;        // part from a train's own bins (traction and braking in one bin)
  double mu_J_per_s = 0.0;    // multiplier of the best bound found
  int evaluations = 0;
};

// P(d) for whole-second distances d = 0..max_distance_s (J): the energy two trains d apart
// could exchange.
std::vector<double> pair_exchange_J(const PowerProfile& profile, int max_distance_s);

// The pair sum of one timetable: self terms plus P(t_j - t_i) over all pairs. Every bound built
// on pairs of trains is at least the largest pair sum of any timetable, so the pair sum of the
// best timetable found shows how far such a bound can at best come down.
double pair_sum_J(const PowerProfile& profile, const std::vector<int>& departures_s);

// Over every timetable within the limits (peak classes relaxed to one range covering both).
PairBound used_regen_bound(const PowerProfile& profile, const FleetLimits& limits);

}  // namespace ecorail::energy
