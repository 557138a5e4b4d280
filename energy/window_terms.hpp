// The pieces the window bound (energy/window_bound.hpp) and the exact headway refinement
// (energy/window_refine.hpp) share: a trip's power on a grid of whole-second fractions, the
// seconds it draws or feeds power for (L), the core (headways of at least L / 4, where at most
// four trains share the line), and the exact window terms on a grid. On a timetable whose every
// four consecutive headways sum to at least L, the used energy on the grid is exactly
//   S(h_1, h_2) + sum_{j=3..n} W(h_{j-2}, h_{j-1}, h_j) + E(h_{n-1}, h_n)
// (n headways): S the first two windows (one train, then two), W a window of the newest three
// trains plus the exact increment the fourth newest adds from then on, E the last window (the
// newest three to the end).
#pragma once

#include <limits>
#include <vector>

#include "energy/model_options.hpp"
#include "energy/power_flow_profile.hpp"

namespace ecorail::energy::window_terms {

// No value: below every energy (a DP state no sequence reaches).
inline constexpr double kNone = -std::numeric_limits<double>::infinity();

// Traction and regenerated energy (J) of one train per bin of a grid of q bins a second.
struct Grid {
  int q = 1;
  long bins = 0;
  std::vector<double> R, T;
  double r(long i) const { return i >= 0 && i < bins ? R[static_cast<std::size_t>(i)] : 0.0; }
  double t(long i) const { return i >= 0 && i < bins ? T[static_cast<std::size_t>(i)] : 0.0; }
};

// The profile on q bins a second (q divides the profile's ticks per second).
Grid grid_of(const PowerProfile& profile, int q);

// The largest divisor of tps that is at most want.
int divisor_at_most(int tps, int want);

// L: from a departure to the end of the last bin with power, in whole seconds.
int active_seconds(const PowerProfile& profile);

// The least headway of the core: four of them span L, so no train is ever fifth newest.
int core_min_s(int active_s, const FleetLimits& limits);

// The exact window terms of the header on one grid (each a pure function of its headways, in
// whole seconds).
class ExactTerms {
 public:
  ExactTerms(const PowerProfile& profile, int q);
  double S(int h1, int h2) const;
  double W(int a, int b, int c) const;
  double E(int a, int b) const;
  // W(a, b, c) for c = c_lo..c_hi into out[0..c_hi - c_lo], the window of three summed once.
  void W_row(int a, int b, int c_lo, int c_hi, double* out) const;
  // W's second part: what the oldest of the window's three (the fourth newest once the next
  // train departs, a + b + c after it) adds from then on.
  double fourth(int a, int b, int c) const;
  // The whole sum for a sequence of at least two headways.
  double value_J(const std::vector<int>& headways_s) const;

 private:
  // Used energy of three trains (newest at offset u, the others off_mid and off_old bins
  // older) over bins [from, upto).
  double three(long off_mid, long off_old, long from, long upto) const;
  Grid g_;
  std::vector<long> nonzero_;     // bins with power
  std::vector<double> self_cum_;  // one train alone: used energy of its first u bins
};

}  // namespace ecorail::energy::window_terms
