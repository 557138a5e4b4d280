// Exact choice of whole-second headways under a fixed sum, by dynamic programming. n headways
// h_1..h_n lie in [min, max] and add up to `sum`; write h = min + e, so the e add up to
// D = sum - n min. The DP runs over the partial sum of e, which after k headways can only lie in
// a band [max(0, D - (n-k) W), min(D, k W)] (W = max - min), so its cost is n x band x W: with
// question 2.1's numbers (99 headways, mean 645 s close to the 660 s maximum) the band is 1440
// wide, not 52 000.
//   maximise_separable: maximise sum_k value(h_k) (the overlap model, train ahead only).
//   maximise_chain: maximise sum_k value(h_k) - sum_k penalty(h_k, h_{k+1}) with penalty >= 0
//   (the overlap model's union variant: the penalty removes the double count when both
//   neighbours draw traction at once). The state carries the last headway; the inner maximum
//   max_e [V(s, e) - penalty(e, e')] walks the candidates e by falling V and stops as soon as
//   V(e) cannot beat the best found, which with a sparse, non-negative penalty takes a step or
//   two. Both are exact; tests compare them with brute force.
#pragma once

#include <limits>
#include <vector>

namespace ecorail::fleet {

// The value of a DP state no headway sequence reaches (both headway DPs, fleet/windowed_dp.hpp).
inline constexpr double kUnreached = -std::numeric_limits<double>::infinity();

struct HeadwayDomain {
  int count = 0;  // headways (trains - 1)
  int min_s = 0, max_s = 0;
  int sum_s = 0;
  int width() const { return max_s - min_s; }
};

struct HeadwayChoice {
  std::vector<int> headways_s;
  double value = 0.0;
  long states = 0;  // DP states visited
};

// value[e] is the value of headway min + e (e = 0..W).
HeadwayChoice maximise_separable(const HeadwayDomain& domain, const std::vector<double>& value);
// penalty[e * (W + 1) + e2] >= 0 for consecutive headways min + e, min + e2. Throws
// std::length_error when the DP would need more than max_states states (the band is wide).
HeadwayChoice maximise_chain(const HeadwayDomain& domain, const std::vector<double>& value,
                             const std::vector<double>& penalty, long max_states = 400'000'000);

}  // namespace ecorail::fleet
