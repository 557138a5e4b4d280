#include "energy/window_terms.hpp"

#include <algorithm>

namespace ecorail::energy::window_terms {

Grid grid_of(const PowerProfile& p, int q) {
  const int tps = p.ticks_per_second();
  const int per = tps / q;
  Grid g;
  g.q = q;
  g.bins = (p.span_bins() + per - 1) / per + 1;
  std::vector<MicroJoules> r(g.bins, 0), t(g.bins, 0);
  for (const PowerBin& b : p.bins()) {
    r[b.offset / per] += b.regen;
    t[b.offset / per] += b.traction;
  }
  g.R.resize(g.bins);
  g.T.resize(g.bins);
  for (long i = 0; i < g.bins; ++i) g.R[i] = to_joules(r[i]), g.T[i] = to_joules(t[i]);
  return g;
}

int divisor_at_most(int tps, int want) {
  for (int q = std::min(tps, want); q > 1; --q)
    if (tps % q == 0) return q;
  return 1;
}

int active_seconds(const PowerProfile& profile) {
  const int tps = profile.ticks_per_second();
  long last = 0;
  for (const PowerBin& b : profile.bins()) last = std::max<long>(last, b.offset);
  return static_cast<int>((last + tps) / tps);  // ceil((last + 1) / tps)
}

int core_min_s(int active_s, const FleetLimits& p) {
  return std::clamp((active_s + 3) / 4, p.headway_min_s, p.headway_max_s + 1);
}

ExactTerms::ExactTerms(const PowerProfile& profile, int q) : g_(grid_of(profile, q)) {
  for (long i = 0; i < g_.bins; ++i)
    if (g_.R[i] != 0.0 || g_.T[i] != 0.0) nonzero_.push_back(i);
  self_cum_.assign(g_.bins + 1, 0.0);
  for (long u = 0; u < g_.bins; ++u) self_cum_[u + 1] = self_cum_[u] + std::min(g_.r(u), g_.t(u));
}

double ExactTerms::three(long off_mid, long off_old, long from, long upto) const {
  double s = 0.0;
  for (long u = from; u < upto; ++u)
    s += std::min(g_.r(u) + g_.r(u + off_mid) + g_.r(u + off_old),
                  g_.t(u) + g_.t(u + off_mid) + g_.t(u + off_old));
  return s;
}

double ExactTerms::S(int h1, int h2) const {
  const long q = g_.q;
  // Train 1 alone over h1, then trains 2 and 1 over h2 (the third "train" lies past the grid,
  // where it has no power).
  return self_cum_[std::min<long>(h1 * q, g_.bins)] + three(h1 * q, g_.bins, 0, h2 * q);
}

double ExactTerms::W(int a, int b, int c) const {
  double w = 0.0;
  W_row(a, b, c, c, &w);
  return w;
}

void ExactTerms::W_row(int a, int b, int c_lo, int c_hi, double* out) const {
  const long q = g_.q;
  double s = three(b * q, (a + b) * q, 0, c_lo * q);
  for (int c = c_lo; c <= c_hi; ++c) {
    if (c > c_lo) s += three(b * q, (a + b) * q, (c - 1) * q, c * q);
    out[c - c_lo] = s + fourth(a, b, c);
  }
}

double ExactTerms::fourth(int a, int b, int c) const {
  const long q = g_.q;
  double v = 0.0;
  const long s3 = (static_cast<long>(a) + b + c) * q;
  for (auto it = std::lower_bound(nonzero_.begin(), nonzero_.end(), s3); it != nonzero_.end();
       ++it) {
    const long tau = *it;
    const double r3 = g_.r(tau - a * q) + g_.r(tau - (a + b) * q) + g_.r(tau - s3);
    const double t3 = g_.t(tau - a * q) + g_.t(tau - (a + b) * q) + g_.t(tau - s3);
    v += std::min(g_.R[tau] + r3, g_.T[tau] + t3) - std::min(r3, t3);
  }
  return v;
}

double ExactTerms::E(int a, int b) const {
  const long q = g_.q;
  return three(b * q, (a + b) * q, 0, g_.bins);
}

double ExactTerms::value_J(const std::vector<int>& h) const {
  const std::size_t n = h.size();
  if (n < 2) return 0.0;
  double v = S(h[0], h[1]);
  for (std::size_t j = 2; j < n; ++j) v += W(h[j - 2], h[j - 1], h[j]);
  return v + E(h[n - 2], h[n - 1]);
}

}  // namespace ecorail::energy::window_terms
