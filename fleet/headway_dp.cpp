#include "fleet/headway_dp.hpp"

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <stdexcept>

namespace ecorail::fleet {

namespace {

struct Band {
  long lo = 0, hi = 0;  // partial sums of e after k headways
};

std::vector<Band> bands(const HeadwayDomain& d) {
  if (d.count < 0 || d.max_s < d.min_s) throw std::invalid_argument("bad headway domain");
  const long n = d.count, w = d.width(), deficit = static_cast<long>(d.sum_s) - n * d.min_s;
  if (deficit < 0 || deficit > n * w)
    throw std::invalid_argument("no headways in the domain reach the sum");
  std::vector<Band> b(n + 1);
  for (long k = 0; k <= n; ++k)
    b[k] = {std::max(0L, deficit - (n - k) * w), std::min(deficit, k * w)};
  return b;
}

}  // namespace

HeadwayChoice maximise_separable(const HeadwayDomain& d, const std::vector<double>& value) {
  const std::vector<Band> band = bands(d);
  const int w = d.width();
  if (static_cast<int>(value.size()) != w + 1) throw std::invalid_argument("value table size");
  HeadwayChoice out;
  // best[s - lo] after k headways; choice[k][s - lo] the e of headway k that reached it.
  std::vector<double> best{0.0}, next;
  std::vector<std::vector<std::int32_t>> choice(d.count + 1);
  for (int k = 1; k <= d.count; ++k) {
    const Band prev = band[k - 1], cur = band[k];
    next.assign(cur.hi - cur.lo + 1, kUnreached);
    choice[k].assign(next.size(), -1);
    for (long s = cur.lo; s <= cur.hi; ++s) {
      double& b = next[s - cur.lo];
      std::int32_t& c = choice[k][s - cur.lo];
      const long e_lo = std::max(0L, s - prev.hi), e_hi = std::min<long>(w, s - prev.lo);
      for (long e = e_lo; e <= e_hi; ++e) {
        const double v = best[s - e - prev.lo] + value[e];
        if (v > b) b = v, c = static_cast<std::int32_t>(e);
      }
      out.states += e_hi - e_lo + 1;
    }
    best.swap(next);
  }
  out.value = best.front();
  out.headways_s.assign(d.count, 0);
  long s = band[d.count].lo;
  for (int k = d.count; k >= 1; --k) {
    const int e = choice[k][s - band[k].lo];
    out.headways_s[k - 1] = d.min_s + e;
    s -= e;
  }
  return out;
}

HeadwayChoice maximise_chain(const HeadwayDomain& d, const std::vector<double>& value,
                             const std::vector<double>& penalty, long max_states) {
  const std::vector<Band> band = bands(d);
  const int w = d.width(), m = w + 1;
  if (static_cast<int>(value.size()) != m || static_cast<long>(penalty.size()) != long(m) * m)
    throw std::invalid_argument("value or penalty table size");
  long states = 0;
  for (int k = 1; k <= d.count; ++k) states += (band[k].hi - band[k].lo + 1) * m;
  if (states > max_states)
    throw std::length_error("the chain DP would need " + std::to_string(states) +
                            " states (the headway sum leaves too wide a band)");
  HeadwayChoice out;
  out.states = states;
  if (d.count == 0) return out;
  // V_k(s, e): best value of k headways whose e add to s and whose last is e.
  std::vector<std::vector<double>> v(d.count + 1);
  std::vector<std::vector<std::int16_t>> from(d.count + 1);  // the e before it
  auto at = [&](int k, long s, int e) -> std::size_t {
    return static_cast<std::size_t>((s - band[k].lo) * m + e);
  };
  v[1].assign((band[1].hi - band[1].lo + 1) * m, kUnreached);
  for (long s = band[1].lo; s <= band[1].hi; ++s)
    if (s <= w) v[1][at(1, s, static_cast<int>(s))] = value[s];
  std::vector<int> order(m);
  for (int k = 1; k < d.count; ++k) {
    const Band cur = band[k], nxt = band[k + 1];
    v[k + 1].assign((nxt.hi - nxt.lo + 1) * m, kUnreached);
    from[k + 1].assign(v[k + 1].size(), -1);
    for (long s = cur.lo; s <= cur.hi; ++s) {
      const double* row = &v[k][at(k, s, 0)];
      int count = 0;
      for (int e = 0; e < m; ++e)
        if (row[e] != kUnreached) order[count++] = e;
      if (count == 0) continue;
      std::sort(order.begin(), order.begin() + count,
                [&](int a, int b) { return row[a] > row[b] || (row[a] == row[b] && a < b); });
      const long e2_lo = std::max(0L, nxt.lo - s), e2_hi = std::min<long>(w, nxt.hi - s);
      for (long e2 = e2_lo; e2 <= e2_hi; ++e2) {
        double best = kUnreached;
        int arg = -1;
        for (int i = 0; i < count; ++i) {
          const int e = order[i];
          if (row[e] <= best) break;  // penalty >= 0: no later candidate can do better
          const double cand = row[e] - penalty[static_cast<std::size_t>(e) * m + e2];
          if (cand > best) best = cand, arg = e;
        }
        const std::size_t j = at(k + 1, s + e2, static_cast<int>(e2));
        const double total = best + value[e2];
        if (total > v[k + 1][j])
          v[k + 1][j] = total, from[k + 1][j] = static_cast<std::int16_t>(arg);
      }
    }
    v[k].clear();
    v[k].shrink_to_fit();
  }
  const long s_end = band[d.count].lo;
  int e_end = 0;
  double best = kUnreached;
  for (int e = 0; e < m; ++e) {
    const double x = v[d.count][at(d.count, s_end, e)];
    if (x > best) best = x, e_end = e;
  }
  out.value = best;
  out.headways_s.assign(d.count, 0);
  long s = s_end;
  int e = e_end;
  for (int k = d.count; k >= 1; --k) {
    out.headways_s[k - 1] = d.min_s + e;
    const int before = k > 1 ? from[k][at(k, s, e)] : 0;
    s -= e;
    e = before;
  }
  return out;
}

}  // namespace ecorail::fleet
