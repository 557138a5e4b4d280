#include "energy/window_refine.hpp"

#include <omp.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdint>
#include <limits>
#include <map>
#include <numeric>
#include <stdexcept>

#include "energy/window_terms.hpp"

namespace ecorail::energy {

namespace {

using window_terms::kNone;

using Triple = std::array<int, 3>;

// The window terms the passes read, kept from pass to pass: every W of three consecutive
// candidates (computed in parallel, each a pure function, so the values do not depend on the
// thread count) and the S and E of the ends.
struct TermCache {
  std::map<Triple, double> W;
  std::map<std::array<int, 2>, double> S, E;
};

// Adds the terms a pass from h reads (each headway within +-d, in [lo, hi]) to the cache.
void compute_terms(const window_terms::ExactTerms& terms, const std::vector<int>& h, int d, int lo,
                   int hi, int threads, TermCache& cache) {
  const int n = static_cast<int>(h.size());
  const auto in = [&](int x) { return x >= lo && x <= hi; };
  std::vector<Triple> wanted;
  for (int j = 2; j < n; ++j)
    for (int a = -d; a <= d; ++a)
      for (int b = -d; b <= d; ++b)
        for (int c = -d; c <= d; ++c) {
          const Triple t{h[j - 2] + a, h[j - 1] + b, h[j] + c};
          if (std::all_of(t.begin(), t.end(), in) && !cache.W.count(t)) wanted.push_back(t);
        }
  std::sort(wanted.begin(), wanted.end());
  wanted.erase(std::unique(wanted.begin(), wanted.end()), wanted.end());
  std::vector<double> values(wanted.size());
#pragma omp parallel for schedule(dynamic, 16) num_threads(threads)
  for (long i = 0; i < static_cast<long>(wanted.size()); ++i)
    values[i] = terms.W(wanted[i][0], wanted[i][1], wanted[i][2]);
  for (std::size_t i = 0; i < wanted.size(); ++i) cache.W.emplace(wanted[i], values[i]);
  for (int a = -d; a <= d; ++a)
    for (int b = -d; b <= d; ++b) {
      const int x = h[0] + a, y = h[1] + b, u = h[n - 2] + a, v = h[n - 1] + b;
      if (in(x) && in(y) && !cache.S.count({x, y})) cache.S[{x, y}] = terms.S(x, y);
      if (in(u) && in(v) && !cache.E.count({u, v})) cache.E[{u, v}] = terms.E(u, v);
    }
}

// One pass: the best changes (each within +-d, the sum kept, partial sums within +-C) of h.
// Returns the best value; *changes the changes.
double best_changes(const std::vector<int>& h, int d, int C, int lo, int hi, const TermCache& t,
                    std::vector<int>* changes) {
  const int n = static_cast<int>(h.size());
  const int w = 2 * d + 1, cw = 2 * C + 1;
  const auto at = [&](int a, int b, int c) {
    return (static_cast<std::size_t>(a) * w + b) * cw + c;
  };
  const auto ok = [&](int j, int change) { return h[j] + change >= lo && h[j] + change <= hi; };
  // V(a, b, s): best value with the last two changes a - d, b - d and the sum changed by s - C.
  std::vector<double> V(static_cast<std::size_t>(w) * w * cw, kNone), next(V.size());
  std::vector<std::vector<std::uint8_t>> back(n);
  for (int a = 0; a < w; ++a)
    for (int b = 0; b < w; ++b) {
      const int s = a + b - 2 * d + C;
      if (ok(0, a - d) && ok(1, b - d) && s >= 0 && s < cw)
        V[at(a, b, s)] = t.S.at({h[0] + a - d, h[1] + b - d});
    }
  for (int j = 2; j < n; ++j) {
    std::fill(next.begin(), next.end(), kNone);
    back[j].assign(V.size(), 0);
    for (int b = 0; b < w; ++b)
      for (int c = 0; c < w; ++c) {
        if (!ok(j - 1, b - d) || !ok(j, c - d)) continue;
        for (int a = 0; a < w; ++a) {
          if (!ok(j - 2, a - d)) continue;
          const double term = t.W.at({h[j - 2] + a - d, h[j - 1] + b - d, h[j] + c - d});
          for (int s = std::max(0, d - c); s < std::min(cw, cw + d - c); ++s) {
            const double v = V[at(a, b, s)];
            if (v == kNone) continue;
            double& slot = next[at(b, c, s + c - d)];
            if (v + term > slot) {
              slot = v + term;
              back[j][at(b, c, s + c - d)] = static_cast<std::uint8_t>(a);
            }
          }
        }
      }
    V.swap(next);
  }
  double best = kNone;
  int best_a = d, best_b = d;
  for (int a = 0; a < w; ++a)
    for (int b = 0; b < w; ++b) {
      const double v = V[at(a, b, C)];
      if (v == kNone) continue;
      const double e = v + t.E.at({h[n - 2] + a - d, h[n - 1] + b - d});
      if (e > best) best = e, best_a = a, best_b = b;
    }
  changes->assign(n, 0);
  (*changes)[n - 1] = best_b - d;
  (*changes)[n - 2] = best_a - d;
  int s = C;
  for (int j = n - 1; j >= 2; --j) {
    const int a = back[j][at((*changes)[j - 1] + d, (*changes)[j] + d, s)];
    s -= (*changes)[j];
    (*changes)[j - 2] = a - d;
  }
  return best;
}

}  // namespace

bool WindowRefineOptions::IsValid(std::string* error) const {
  auto fail = [&](const std::string& why) {
    if (error) *error = why;
    return false;
  };
  if (max_step_s < 1 || max_step_s > 20) return fail("max_step_s: expected 1 to 20 s");
  if (max_shift_s < 0 || max_shift_s > 1000) return fail("max_shift_s: expected 0 to 1000 s");
  if (max_passes < 1 || max_passes > 1000) return fail("max_passes: expected 1 to 1000");
  if (!(time_limit_s >= 0.0)) return fail("time_limit_s: expected 0 (none) or more seconds");
  if (threads < 0 || threads > 1024) return fail("threads: expected 0 (default) to 1024");
  return true;
}

WindowRefineSummary window_refine(const PowerProfile& profile, const FleetLimits& p,
                                  const std::vector<int>& headways_s,
                                  const WindowRefineOptions& o) {
  const auto t0 = std::chrono::steady_clock::now();
  const auto elapsed = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  };
  std::string why;
  if (!o.IsValid(&why)) throw std::invalid_argument(why);
  WindowRefineSummary out;
  out.headways_s = headways_s;
  const int lo =
      std::max(p.headway_min_s, window_terms::core_min_s(window_terms::active_seconds(profile), p));
  const int hi = p.headway_max_s;
  const long sum = std::accumulate(headways_s.begin(), headways_s.end(), 0L);
  if (profile.sections() != 1)
    out.why_not = "more than one supply section";
  else if (static_cast<int>(headways_s.size()) != p.trains - 1 || p.trains < 3)
    out.why_not = "one headway per pair of at least three trains expected";
  else if (sum != p.span_s)
    out.why_not = "the headways do not sum to the span";
  else if (std::any_of(headways_s.begin(), headways_s.end(),
                       [&](int h) { return h < lo || h > hi; }))
    out.why_not =
        "a headway outside the core (" + std::to_string(lo) + " to " + std::to_string(hi) + " s)";
  if (!out.why_not.empty()) return out;
  out.applicable = true;
  const int threads = o.threads > 0 ? o.threads : omp_get_max_threads();
  const window_terms::ExactTerms terms(profile, profile.ticks_per_second());
  out.start_used_J = out.used_J = terms.value_J(headways_s);
  TermCache cache;
  std::vector<int> changes;
  for (int pass = 0; pass < o.max_passes; ++pass) {
    if (o.time_limit_s > 0.0 && elapsed() > o.time_limit_s) {
      out.time_limit_reached = true;
      break;
    }
    compute_terms(terms, out.headways_s, o.max_step_s, lo, hi, threads, cache);
    best_changes(out.headways_s, o.max_step_s, o.max_shift_s, lo, hi, cache, &changes);
    ++out.passes;
    std::vector<int> next = out.headways_s;
    for (std::size_t j = 0; j < next.size(); ++j) next[j] += changes[j];
    // The DP's sum and this one add the same terms in another order: a gain is taken only when
    // it is more than their rounding.
    const double value = terms.value_J(next);
    if (!(value > out.used_J + 1e-9 * out.used_J + 1e-3)) break;
    out.headways_s = std::move(next);
    out.used_J = value;
  }
  out.window_terms = static_cast<long>(cache.W.size());
  out.wall_s = elapsed();
  return out;
}

}  // namespace ecorail::energy
