// A proven upper bound on the regenerated energy any timetable of a one-class problem can use in
// the power-flow model (one supply section): the power-flow model's certificate when it applies
// (energy/power_flow_model.hpp). It rests on four facts.
//  1. A coarser grid never uses less: a bin of the bound's grid (0.5 s by default) is a union
//     of the model's bins, and sum_b min(R_b, T_b) <= min(sum_b R_b, sum_b T_b), so the used
//     energy on the bound's grid is at least the model's (departures are whole seconds, so the
//     grids stay aligned). Coarsening only loosens the bound; it makes its tables cheaper.
//  2. Windows: between the departures of trains j and j+1 (window j, length h_j) order the
//     trains on the line newest first. The used energy of a bin is the min of the newest three
//     (trains j-2, j-1, j: a function G3 of h_{j-2}, h_{j-1}, h_j), plus the exact increment of
//     the fourth newest (train k = j-3, whose position relative to trains k+1..k+3 is fixed by
//     h_k, h_{k+1}, h_{k+2}: a function X4 of those three), plus for every older train at most
//     max(R, T) of that train in the bin (min(x + a, y + b) - min(x, y) <= max(a, b)). A train
//     draws or feeds power for L seconds after its departure (about the trip time); when every
//     four consecutive headways sum to at least L no train is ever fifth newest, and used =
//     sum_j G3 + sum_k X4 exactly: a sum of functions of three consecutive headways. Every
//     headway of at least L/4 (the "core") guarantees it.
//  3. The rest of the domain: train k can be fifth newest only when h_k..h_{k+3} sum below L.
//     What it adds from t_{k+4} on is charged at the DP step that adds h_{k+3}, which knows
//     h_{k+1..k+3} and the class of h_k (the core or one of a few bands below it, kept in the
//     DP state), at its largest value for that class: the tighter of the sum of max(R, T) over
//     the rest of its run and a sum of pairs (adding train k to the newer trains of a bin adds at
//     most its own min(R, T) plus, for each newer train i, min(R_k, T_i) + min(T_k, R_i)), each
//     newer train at the gaps the cells and the class allow. Triples with a headway below the
//     core are valued on a 1 s grid with the fourth train by pairs (min(a, T_N3) <=
//     sum_i min(a, T_i)), headways below the core grouped in cells at their largest value, and
//     a triple whose shortfall below 3 headway_max_s exceeds the whole span's is left out (no
//     feasible timetable holds it). So the bound holds over EVERY timetable within the limits,
//     with no assumption; it is exact (up to fact 1's grid and fact 4's multiplier) on the
//     timetables whose headways all lie in the core.
//  4. A DP over the last two headways (and the class bit) maximises the sum of those terms with
//     the fixed sum of headways priced by a Lagrange multiplier mu: every mu gives a valid bound
//     (weak duality). The dual is convex and piecewise linear in mu with the maximiser's excess
//     over the span as subgradient: mu is bracketed, then set where the bracket's tangents
//     cross, until the best bound is within multiplier_tolerance of that crossing (no mu can
//     give less).
// The DP's maximisers (a headway sequence for each multiplier tried) are starts for a search
// when every headway lies in the core (window_core_maximisers).
#pragma once

#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "energy/model_options.hpp"
#include "energy/power_flow_profile.hpp"

namespace ecorail::energy {

struct WindowBoundOptions {
  int bound_ticks_per_second = 2;  // grid of the core's exact windows (divides the profile's)
  int short_cell_s = 10;           // width of the cells below the core (s)
  // Classes of the headway before the DP state's two, below the core: bands ending this many
  // seconds below it (ascending), one more for the rest. A fifth train's charge is the largest
  // over its band; each band is one more class in the DP, whose time grows with the classes
  // (the reference bound: 5.4 s wall with 2 classes, 13.5 s with these 8; docs/performance.md).
  std::vector<int> short_band_ends_s = {20, 60, 100, 140, 200, 280};
  int max_dual_evaluations = 24;  // DP runs of the multiplier search
  // The multiplier search stops when no multiplier can lower the bound by more than this
  // fraction of it (the crossing of the bracket's tangents shows how much one could).
  double multiplier_tolerance = 1e-5;
  int threads = 0;  // 0: OpenMP's default
  // Asked (from any thread) while the tables are built and before each DP layer; once it
  // returns true the bound ends (WindowBound::stopped). Empty: never.
  std::function<bool()> stop;
  bool IsValid(std::string* error) const;
};

struct WindowBound {
  bool applicable = false;  // one class, one supply section, at least three trains
  std::string why_not;      // when not applicable
  // `stop` ended it: bound_used_J is then the best multiplier's of the DP runs that finished
  // (still a bound: every multiplier gives one), and the bound is not applicable when none did.
  bool stopped = false;
  double bound_used_J = 0.0;  // valid upper bound on the used regenerated energy
  double mu_J_per_s = 0.0;    // multiplier of the best bound
  double active_s = 0.0;      // L: from a departure to the last bin with power
  int core_min_s = 0;         // headways from here up are the exact core
  int evaluations = 0;        // DP runs
  // No multiplier gives a bound below this (the convex dual's tangents; -inf when the search
  // did not bracket its minimum).
  double dual_floor_J = -std::numeric_limits<double>::infinity();
  long dp_transitions = 0;
  double wall_s = 0.0;
  double tables_s = 0.0;  // building the window terms (the rest is the multiplier search)
  // The relaxed problem's maximisers (one per multiplier tried, sums on both sides of the span;
  // headways of short cells at the cell's end that the multiplier favours).
  std::vector<std::vector<int>> maximisers;
  // The maximiser at the best multiplier.
  std::vector<int> best_maximiser;
};

WindowBound window_used_regen_bound(const PowerProfile& profile, const FleetLimits& problem,
                                    const WindowBoundOptions& options = {});

// What a stopped bound (WindowBound::stopped) did, for a bound's name: "the window bound cut
// short by the time limit after 3 DP runs".
std::string window_cut_short(const WindowBound& bound);

// The maximisers of the same relaxation with every headway in the core (at most four trains on
// the line, where the window terms are exact): starts for a search (fleet/relaxed_start.hpp).
// The full relaxation's own maximisers are no starts: they crowd into the short headways it
// overstates. Empty when the bound does not apply or the core cannot hold the span.
std::vector<std::vector<int>> window_core_maximisers(const PowerProfile& profile,
                                                     const FleetLimits& problem,
                                                     const WindowBoundOptions& options = {});

// The relaxed objective of headway sequences (the sum of the window terms and charges on the
// bound's grid, no multiplier): at least the used energy of each timetable on the model's grid,
// equal to it on the bound's grid when every headway lies in the core (tests).
std::vector<double> window_relaxed_values_J(const PowerProfile& profile, const FleetLimits& problem,
                                            const std::vector<std::vector<int>>& headways_s,
                                            const WindowBoundOptions& options = {});

}  // namespace ecorail::energy
