#include "energy/window_span_optimum.hpp"

#include <omp.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <limits>
#include <numeric>
#include <stdexcept>

#include "energy/window_terms.hpp"

namespace ecorail::energy {

namespace {

using window_terms::kNone;

// The window terms of every headway of the range (index i is headway lo + i).
struct Terms {
  int K = 0;
  std::vector<double> W, S, E;  // W[(a K + b) K + c], S[a K + b], E[a K + b]
  double w(int a, int b, int c) const { return W[(static_cast<std::size_t>(a) * K + b) * K + c]; }
};

// Every term, rows of (a, b) in parallel; false when over_time (called between rows, with the
// rows done so far) says to stop.
bool all_terms(const window_terms::ExactTerms& exact, int lo, int K, int threads,
               const std::function<bool(long)>& over_time, Terms& t) {
  t.K = K;
  t.W.assign(static_cast<std::size_t>(K) * K * K, 0.0);
  t.S.assign(static_cast<std::size_t>(K) * K, 0.0);
  t.E.assign(t.S.size(), 0.0);
  std::atomic<long> done{0};
  std::atomic<bool> stop{false};
  // Rows in a scattered order (a step prime to their count), so that the first ones, from which
  // the cost is projected, are not all the short headways' (the dearest: the fourth train's
  // increment runs from a + b + c to the end of its power).
  const long rows = static_cast<long>(K) * K;
  long step = 7919;
  while (std::gcd(step, rows) != 1) ++step;
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads)
  for (long i = 0; i < rows; ++i) {
    if (stop.load(std::memory_order_relaxed)) continue;
    const int ab = static_cast<int>(i * step % rows);
    const int a = ab / K, b = ab % K;
    exact.W_row(lo + a, lo + b, lo, lo + K - 1, &t.W[static_cast<std::size_t>(ab) * K]);
    t.S[ab] = exact.S(lo + a, lo + b);
    t.E[ab] = exact.E(lo + a, lo + b);
    if (over_time(++done)) stop = true;
  }
  return !stop;
}

// The relaxed problem at multiplier mu: F[j][a K + b] the best value of h_0..h_j ending in
// (a, b) less mu times their sum; sum_of_best the sum of the overall maximiser's headways.
struct Relaxed {
  std::vector<std::vector<double>> F;
  double value = kNone;  // L(mu) = max (F[n-1] + E) + mu span
  long sum_of_best = 0;
};

Relaxed relaxed_forward(const Terms& t, int lo, int n, long span, double mu, int threads) {
  const int K = t.K;
  Relaxed r;
  r.F.assign(n, {});
  std::vector<long> sums(static_cast<std::size_t>(K) * K), next_sums(sums.size());
  r.F[1].assign(static_cast<std::size_t>(K) * K, kNone);
  for (int a = 0; a < K; ++a)
    for (int b = 0; b < K; ++b) {
      r.F[1][a * K + b] = t.S[a * K + b] - mu * (2 * lo + a + b);
      sums[a * K + b] = 2 * lo + a + b;
    }
  for (int j = 2; j < n; ++j) {
    const std::vector<double>& F = r.F[j - 1];
    std::vector<double>& G = r.F[j];
    G.assign(F.size(), kNone);
#pragma omp parallel for schedule(static) num_threads(threads)
    for (int bc = 0; bc < K * K; ++bc) {
      const int b = bc / K, c = bc % K;
      double best = kNone;
      long best_sum = 0;
      for (int a = 0; a < K; ++a) {
        const double v = F[a * K + b] + t.w(a, b, c);
        if (v > best) best = v, best_sum = sums[a * K + b];
      }
      G[bc] = best - mu * (lo + c);
      next_sums[bc] = best_sum + lo + c;
    }
    sums.swap(next_sums);
  }
  for (int ab = 0; ab < K * K; ++ab) {
    const double v = r.F[n - 1][ab] + t.E[ab] + mu * static_cast<double>(span);
    if (v > r.value) r.value = v, r.sum_of_best = sums[ab];
  }
  return r;
}

// G[j][a K + b]: the best value after h_j (terms from j + 1 on and E) less mu times the sum of
// h_{j+1}..h_{n-1}, given h_{j-1} = a and h_j = b.
std::vector<std::vector<double>> relaxed_backward(const Terms& t, int lo, int n, double mu,
                                                  int threads) {
  const int K = t.K;
  std::vector<std::vector<double>> G(n);
  G[n - 1] = t.E;
  for (int j = n - 2; j >= 1; --j) {
    G[j].assign(static_cast<std::size_t>(K) * K, kNone);
#pragma omp parallel for schedule(static) num_threads(threads)
    for (int ab = 0; ab < K * K; ++ab) {
      const int a = ab / K, b = ab % K;
      double best = kNone;
      for (int c = 0; c < K; ++c)
        best = std::max(best, t.w(a, b, c) - mu * (lo + c) + G[j + 1][b * K + c]);
      G[j][ab] = best;
    }
  }
  return G;
}

}  // namespace

bool WindowSpanOptions::IsValid(std::string* error) const {
  auto fail = [&](const std::string& why) {
    if (error) *error = why;
    return false;
  };
  if (lowest_headway_s < 0) return fail("lowest_headway_s: expected 0 (the core) or more s");
  if (max_dual_evaluations < 2 || max_dual_evaluations > 1000)
    return fail("max_dual_evaluations: expected 2 to 1000");
  if (threads < 0 || threads > 1024) return fail("threads: expected 0 (default) to 1024");
  if (!(time_limit_s >= 0.0) || !std::isfinite(time_limit_s))
    return fail("time_limit_s: expected 0 (none) or more seconds");
  return true;
}

std::string WindowSpanSummary::BriefReport() const {
  if (!applicable) return "exact optimum of the core not applicable: " + why_not;
  char buf[400];
  std::snprintf(buf, sizeof buf,
                "exact optimum over headways %d-%d s: used %.1f kJ (%s), relaxed bound %.1f kJ, "
                "%ld states",
                lowest_headway_s, highest_headway_s, used_J / 1e3,
                improved ? "better than the incumbent" : "the incumbent is optimal",
                dual_bound_J / 1e3, exact_states);
  return buf;
}

WindowSpanSummary window_span_optimum(const PowerProfile& profile, const FleetLimits& p,
                                      const std::vector<int>& incumbent_s,
                                      const WindowSpanOptions& o) {
  const auto t0 = std::chrono::steady_clock::now();
  const auto elapsed = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  };
  std::string why;
  if (!o.IsValid(&why)) throw std::invalid_argument(why);
  WindowSpanSummary out;
  const int core = window_terms::core_min_s(window_terms::active_seconds(profile), p);
  const int lo = std::max({p.headway_min_s, core, o.lowest_headway_s});
  const int hi = p.headway_max_s;
  const int n = p.trains - 1;
  const long span = p.span_s;
  out.lowest_headway_s = lo;
  out.highest_headway_s = hi;
  if (profile.sections() != 1)
    out.why_not = "more than one supply section";
  else if (n < 3)
    out.why_not = "at least four trains expected";
  else if (hi < lo)
    out.why_not = "the range is empty";
  else if (hi - lo + 1 > 256)
    out.why_not = "more than 256 headways in the range";
  else if (span < static_cast<long>(n) * lo || span > static_cast<long>(n) * hi)
    out.why_not = "no timetable of the range meets the span";
  if (!out.why_not.empty()) return out;
  out.applicable = true;
  const int K = hi - lo + 1;
  const int threads = o.threads > 0 ? o.threads : omp_get_max_threads();
  const window_terms::ExactTerms exact(profile, profile.ticks_per_second());

  double incumbent = kNone;
  if (static_cast<int>(incumbent_s.size()) == n &&
      std::accumulate(incumbent_s.begin(), incumbent_s.end(), 0L) == span &&
      std::all_of(incumbent_s.begin(), incumbent_s.end(),
                  [&](int h) { return h >= lo && h <= hi; })) {
    incumbent = exact.value_J(incumbent_s);
    out.headways_s = incumbent_s;
  }
  out.incumbent_used_J = out.used_J = incumbent;

  const double limit = o.time_limit_s;
  const auto out_of_time = [&] { return limit > 0.0 && elapsed() > limit; };
  const auto stopped = [&] {
    out.time_limit_reached = true;
    out.why_not = "the time limit stopped it";
    out.headways_s = incumbent_s;
    out.used_J = out.incumbent_used_J;
    out.wall_s = elapsed();
    return out;
  };
  Terms t;
  const long rows = static_cast<long>(K) * K, probe = std::min<long>(rows, 4L * threads);
  const auto over_time = [&](long done) {
    // The rows' cost from the first ones: stop when the rest would pass 60 % of the limit.
    if (limit <= 0.0) return false;
    const double now = elapsed();
    return now > limit || (done == probe && now * static_cast<double>(rows) / probe > 0.6 * limit);
  };
  if (!all_terms(exact, lo, K, threads, over_time, t)) return stopped();
  out.window_terms = static_cast<long>(t.W.size());
  out.terms_s = elapsed();

  // 1. The multiplier: the relaxed maximiser's sum falls as mu rises; bracket the span, bisect.
  double mu_lo = 0.0, mu_hi = 0.0, best_mu = 0.0;
  Relaxed best_r = relaxed_forward(t, lo, n, span, 0.0, threads);
  out.dual_evaluations = 1;
  auto consider = [&](double mu, Relaxed&& r) {
    if (r.value < best_r.value) best_r = std::move(r), best_mu = mu;
  };
  {
    const bool above = best_r.sum_of_best > span;  // then mu > 0 lowers the sum
    double step = 1e3;
    double mu = 0.0;
    bool bracketed = best_r.sum_of_best == span;
    while (!bracketed && out.dual_evaluations < o.max_dual_evaluations / 2 && !out_of_time()) {
      const double next = above ? mu + step : mu - step;
      Relaxed r = relaxed_forward(t, lo, n, span, next, threads);
      ++out.dual_evaluations;
      const bool crossed = above ? r.sum_of_best <= span : r.sum_of_best >= span;
      consider(next, std::move(r));
      if (crossed) {
        mu_lo = std::min(mu, next), mu_hi = std::max(mu, next);
        bracketed = true;
      } else {
        mu = next;
        step *= 2.0;
      }
    }
    while (bracketed && mu_lo < mu_hi && out.dual_evaluations < o.max_dual_evaluations &&
           !out_of_time()) {
      const double mid = 0.5 * (mu_lo + mu_hi);
      Relaxed r = relaxed_forward(t, lo, n, span, mid, threads);
      ++out.dual_evaluations;
      if (r.sum_of_best > span)
        mu_lo = mid;
      else
        mu_hi = mid;
      consider(mid, std::move(r));
    }
  }
  if (out_of_time()) return stopped();
  out.dual_bound_J = best_r.value;
  out.mu_J_per_s = best_mu;
  const std::vector<std::vector<double>>& F = best_r.F;
  const std::vector<std::vector<double>> G = relaxed_backward(t, lo, n, best_mu, threads);

  // 2. The exact DP over (pair, partial sum), states that cannot beat the incumbent dropped.
  // A state may tie the incumbent within rounding: keep it, so the incumbent's own path lives.
  const double floor_J = incumbent == kNone ? kNone : incumbent - 1e-9 * std::abs(incumbent) - 1.0;
  const double mu = best_mu;
  auto p_lo = [&](int j) {  // least partial sum of h_0..h_j that can still meet the span
    return std::max(static_cast<long>(j + 1) * lo, span - static_cast<long>(n - 1 - j) * hi);
  };
  auto p_hi = [&](int j) {
    return std::min(static_cast<long>(j + 1) * hi, span - static_cast<long>(n - 1 - j) * lo);
  };
  // Per stage: the slot of each pair (-1: dropped) and the values / back pointers of the slots.
  std::vector<std::vector<int>> slot(n, std::vector<int>(static_cast<std::size_t>(K) * K, -1));
  std::vector<std::vector<std::uint8_t>> back(n);
  std::vector<double> cur, next;
  long width = p_hi(1) - p_lo(1) + 1;
  {
    std::vector<int> alive;
    for (int ab = 0; ab < K * K; ++ab) {
      const long P = 2L * lo + ab / K + ab % K;
      if (width <= 0 || P < p_lo(1) || P > p_hi(1)) continue;
      const double v = t.S[ab];
      if (v + G[1][ab] + mu * static_cast<double>(span - P) < floor_J) {
        ++out.pruned_pairs;
        continue;
      }
      slot[1][ab] = static_cast<int>(alive.size());
      alive.push_back(ab);
    }
    cur.assign(alive.size() * std::max(width, 0L), kNone);
    for (std::size_t s = 0; s < alive.size(); ++s) {
      const int ab = alive[s];
      const long P = 2L * lo + ab / K + ab % K;
      cur[s * width + (P - p_lo(1))] = t.S[ab];
      ++out.exact_states;
    }
  }
  for (int j = 2; j < n; ++j) {
    if (out_of_time()) return stopped();
    const long lo_prev = p_lo(j - 1), lo_j = p_lo(j);
    const long w_prev = width, w_j = p_hi(j) - lo_j + 1;
    std::vector<int> cand;  // pairs (b, c) whose relaxed bound reaches the incumbent
    for (int bc = 0; bc < K * K; ++bc) {
      if (w_j <= 0) break;
      if (F[j][bc] + G[j][bc] + mu * static_cast<double>(span) < floor_J) {
        ++out.pruned_pairs;
        continue;
      }
      const int b = bc / K;
      bool fed = false;
      for (int a = 0; a < K && !fed; ++a) fed = slot[j - 1][a * K + b] >= 0;
      if (fed) cand.push_back(bc);
    }
    next.assign(cand.size() * std::max(w_j, 0L), kNone);
    back[j].assign(next.size(), 0);
    std::vector<char> used(cand.size(), 0);
    long states = 0;
#pragma omp parallel for schedule(dynamic, 4) num_threads(threads) reduction(+ : states)
    for (long s = 0; s < static_cast<long>(cand.size()); ++s) {
      const int bc = cand[s];
      const int b = bc / K, c = bc % K;
      const double after = G[j][bc];
      double* out_v = &next[s * w_j];
      std::uint8_t* out_b = &back[j][s * w_j];
      for (int a = 0; a < K; ++a) {
        const int from = slot[j - 1][a * K + b];
        if (from < 0) continue;
        const double term = t.w(a, b, c);
        const double* in = &cur[static_cast<std::size_t>(from) * w_prev];
        for (long i = 0; i < w_prev; ++i) {
          if (in[i] == kNone) continue;
          const long P = lo_prev + i + lo + c;
          const long k = P - lo_j;
          if (k < 0 || k >= w_j) continue;
          const double v = in[i] + term;
          if (v + after + mu * static_cast<double>(span - P) < floor_J) continue;
          if (v > out_v[k]) out_v[k] = v, out_b[k] = static_cast<std::uint8_t>(a);
        }
      }
      for (long k = 0; k < w_j; ++k)
        if (out_v[k] != kNone) ++states, used[s] = 1;
    }
    out.exact_states += states;
    // Keep the pairs with a state, moved down in place; their slots are renumbered in order.
    std::size_t kept = 0;
    for (std::size_t s = 0; s < cand.size(); ++s) {
      if (!used[s]) continue;
      slot[j][cand[s]] = static_cast<int>(kept);
      if (kept != s) {
        std::copy_n(next.begin() + s * w_j, w_j, next.begin() + kept * w_j);
        std::copy_n(back[j].begin() + s * w_j, w_j, back[j].begin() + kept * w_j);
      }
      ++kept;
    }
    next.resize(kept * w_j);
    back[j].resize(kept * w_j);
    cur.swap(next);
    width = w_j;
  }
  // 3. The end: the partial sum is the span.
  double best = kNone;
  int best_ab = -1;
  const long end_k = span - p_lo(n - 1);
  for (int ab = 0; ab < K * K; ++ab) {
    const int s = slot[n - 1][ab];
    if (s < 0 || end_k < 0 || end_k >= width) continue;
    const double v = cur[static_cast<std::size_t>(s) * width + end_k];
    if (v == kNone) continue;
    if (v + t.E[ab] > best) best = v + t.E[ab], best_ab = ab;
  }
  if (best_ab >= 0) {
    std::vector<int> idx(n);
    idx[n - 2] = best_ab / K, idx[n - 1] = best_ab % K;
    long P = span;
    for (int j = n - 1; j >= 2; --j) {
      const int s = slot[j][idx[j - 1] * K + idx[j]];
      idx[j - 2] = back[j][static_cast<std::size_t>(s) * (p_hi(j) - p_lo(j) + 1) + (P - p_lo(j))];
      P -= lo + idx[j];
    }
    std::vector<int> h(n);
    for (int j = 0; j < n; ++j) h[j] = lo + idx[j];
    // The DP's sum and value_J add the same terms in another order: a gain is taken only when it
    // is more than their rounding.
    const double value = exact.value_J(h);
    if (incumbent == kNone || value > incumbent + 1e-9 * std::abs(incumbent) + 1e-3) {
      out.headways_s = std::move(h);
      out.used_J = value;
      out.improved = true;
    }
  }
  out.wall_s = elapsed();
  return out;
}

}  // namespace ecorail::energy
