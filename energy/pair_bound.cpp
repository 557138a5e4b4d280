#include "energy/pair_bound.hpp"

#include "dp/golden_section.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace ecorail::energy {

namespace {

// Dense bins of one profile: traction per (section, bin).
struct Dense {
  long bins = 0;
  int sections = 1;
  std::vector<MicroJoules> traction;
  MicroJoules at(int section, long bin) const {
    return bin < 0 || bin >= bins ? 0 : traction[static_cast<std::size_t>(section) * bins + bin];
  }
};

Dense dense_traction(const PowerProfile& p) {
  Dense d;
  d.bins = p.span_bins();
  d.sections = p.sections();
  d.traction.assign(static_cast<std::size_t>(d.sections) * d.bins, 0);
  for (const PowerBin& b : p.bins())
    d.traction[static_cast<std::size_t>(b.section) * d.bins + b.offset] += b.traction;
  return d;
}

}  // namespace

std::vector<double> pair_exchange_J(const PowerProfile& profile, int max_distance_s) {
  const Dense dense = dense_traction(profile);
  std::vector<double> out(max_distance_s + 1, 0.0);
  const long tps = profile.ticks_per_second();
  for (int d = 0; d <= max_distance_s; ++d) {
    const long shift = d * tps;
    MicroJoules sum = 0;
    for (const PowerBin& b : profile.bins()) {
      if (b.regen == 0) continue;
      // Fed by the traction of a train d behind, and of a train d ahead.
      sum += std::min(b.regen, dense.at(b.section, b.offset - shift));
      sum += std::min(b.regen, dense.at(b.section, b.offset + shift));
    }
    out[d] = to_joules(sum);
  }
  return out;
}

namespace {

int reach_s(const PowerProfile& profile) {
  return static_cast<int>(
             std::ceil(static_cast<double>(profile.span_bins()) / profile.ticks_per_second())) +
         1;
}

double self_J(const PowerProfile& profile) {
  MicroJoules self = 0;
  for (const PowerBin& b : profile.bins()) self += std::min(b.traction, b.regen);
  return to_joules(self);
}

}  // namespace

double pair_sum_J(const PowerProfile& profile, const std::vector<int>& t) {
  const int reach = reach_s(profile);
  const std::vector<double> p = pair_exchange_J(profile, reach);
  double sum = self_J(profile) * static_cast<double>(t.size());
  for (std::size_t i = 0; i < t.size(); ++i)
    for (std::size_t j = i + 1; j < t.size() && t[j] - t[i] <= reach; ++j) sum += p[t[j] - t[i]];
  return sum;
}

PairBound used_regen_bound(const PowerProfile& profile, const FleetLimits& pr) {
  PairBound out;
  const int n = pr.trains - 1;  // headways
  out.self_J = self_J(profile) * pr.trains;
  if (n <= 0) {
    out.bound_used_J = out.self_J;
    return out;
  }
  const int reach = static_cast<int>(std::ceil(static_cast<double>(profile.span_bins()) /
                                               profile.ticks_per_second())) +
                    1;
  const std::vector<double> p = pair_exchange_J(profile, reach);
  auto P = [&](long d) { return d >= 0 && d <= reach ? p[d] : 0.0; };
  const int lo = pr.headway_min_s, hi = pr.headway_max_s, m = hi - lo + 1;
  // far[x]: the most the pairs three or more headways apart can add when the first two of them
  // sum to x: sum over d >= 3 of max over the other d - 2 headways of P(x + their sum).
  std::vector<double> far(2 * hi + 1, 0.0);
  for (int x = 2 * lo; x <= 2 * hi; ++x) {
    double total = 0.0;
    for (int extra = 1; x + extra * lo <= reach && extra < n; ++extra) {
      double best = 0.0;
      for (long y = static_cast<long>(extra) * lo; y <= static_cast<long>(extra) * hi; ++y)
        best = std::max(best, P(x + y));
      total += best;
    }
    far[x] = total;
  }
  // Chain over headways h_1..h_n with multiplier mu on their sum. Step k adds P(h_k) and, for
  // k >= 2, P(h_{k-1} + h_k) + far(h_{k-1} + h_k).
  auto dual = [&](double mu) {
    std::vector<double> v(m), next(m);
    for (int e = 0; e < m; ++e) v[e] = P(lo + e) - mu * (lo + e);
    for (int k = 2; k <= n; ++k) {
      for (int e2 = 0; e2 < m; ++e2) {
        double best = -std::numeric_limits<double>::infinity();
        for (int e = 0; e < m; ++e) {
          const int x = 2 * lo + e + e2;
          best = std::max(best, v[e] + P(x) + far[x]);
        }
        next[e2] = best + P(lo + e2) - mu * (lo + e2);
      }
      v.swap(next);
    }
    ++out.evaluations;
    return *std::max_element(v.begin(), v.end()) + mu * pr.span_s;
  };
  // The dual is convex in mu: golden-section search over a bracket wide enough for any slope.
  const dp::GoldenSectionResult g =
      dp::golden_section_minimum(dual, -2e7, 2e7, 1.0, 60, /*ties_go_left=*/false);
  out.bound_used_J = out.self_J + g.best_f;
  out.mu_J_per_s = g.best_x;
  return out;
}

}  // namespace ecorail::energy
