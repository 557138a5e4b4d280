#include "fleet/relaxed_start.hpp"

#include <algorithm>
#include <cstdlib>
#include <numeric>

namespace ecorail::fleet {

bool spread_to_span(std::vector<int>& headways_s, int span_s, int lo_s, int hi_s) {
  const long n = static_cast<long>(headways_s.size());
  if (n == 0) return false;
  long rest = span_s - std::accumulate(headways_s.begin(), headways_s.end(), 0L);
  if (rest > 0 ? rest > n * hi_s - (span_s - rest) : -rest > (span_s - rest) - n * lo_s)
    return false;
  for (int& h : headways_s)
    if (h < lo_s || h > hi_s) return false;
  // Pass after pass over the day, each headway that can take a second takes one, in an order
  // that visits the day evenly (stride coprime to n), until nothing is missing.
  long stride = std::max(1L, n / 2 + 1);
  while (std::gcd(stride, n) != 1) ++stride;
  while (rest != 0) {
    const int step = rest > 0 ? 1 : -1;
    bool moved = false;
    for (long k = 0, i = 0; k < n && rest != 0; ++k, i = (i + stride) % n) {
      int& h = headways_s[static_cast<std::size_t>(i)];
      if (h + step < lo_s || h + step > hi_s) continue;
      h += step;
      rest -= step;
      moved = true;
    }
    if (!moved) return false;  // unreachable after the capacity check above
  }
  return true;
}

namespace {

// The join of a prefix of a and the suffix of b (k = 0..n) whose sum comes nearest the span (the
// first such k); *miss its distance from the span.
std::vector<int> nearest_join(const std::vector<int>& a, const std::vector<int>& b, long span_s,
                              long* miss) {
  const std::size_t n = a.size();
  // sum(a[0..k)) + sum(b[k..n)) for k = 0..n.
  long joined = std::accumulate(b.begin(), b.end(), 0L);
  std::size_t best_k = 0;
  *miss = -1;
  for (std::size_t k = 0; k <= n; ++k) {
    if (*miss < 0 || std::labs(joined - span_s) < *miss)
      *miss = std::labs(joined - span_s), best_k = k;
    if (k < n) joined += a[k] - b[k];
  }
  std::vector<int> out(a.begin(), a.begin() + static_cast<long>(best_k));
  out.insert(out.end(), b.begin() + static_cast<long>(best_k), b.end());
  return out;
}

// The usable maximisers: one headway per pair of trains.
std::vector<const std::vector<int>*> usable(const std::vector<std::vector<int>>& maximisers_s,
                                            const FleetProblem& p) {
  const std::size_t n = static_cast<std::size_t>(std::max(0, p.trains - 1));
  std::vector<const std::vector<int>*> out;
  for (const auto& m : maximisers_s)
    if (m.size() == n && n > 0) out.push_back(&m);
  return out;
}

// Clamped into the limits and closed to the span (empty when it cannot be).
std::vector<int> closed(std::vector<int> h, const FleetProblem& p) {
  for (int& x : h) x = std::clamp(x, p.headway_min_s, p.headway_max_s);
  if (!spread_to_span(h, p.span_s, p.headway_min_s, p.headway_max_s)) return {};
  return h;
}

}  // namespace

std::vector<int> relaxed_start_headways(const std::vector<std::vector<int>>& maximisers_s,
                                        const FleetProblem& p) {
  // The best join over every ordered pair (a = b: the maximiser itself): the nearest the span.
  const auto m = usable(maximisers_s, p);
  long best_miss = -1;
  std::vector<int> best;
  for (const auto* a : m)
    for (const auto* b : m) {
      long miss = 0;
      std::vector<int> j = nearest_join(*a, *b, p.span_s, &miss);
      if (best_miss < 0 || miss < best_miss) best_miss = miss, best = std::move(j);
    }
  if (best_miss < 0) return {};
  return closed(std::move(best), p);
}

std::vector<std::vector<int>> relaxed_start_candidates(
    const std::vector<std::vector<int>>& maximisers_s, const FleetProblem& p) {
  const auto m = usable(maximisers_s, p);
  std::vector<std::vector<int>> out;
  if (m.empty()) return out;
  const long n = static_cast<long>(m.front()->size());
  for (const auto* a : m)
    for (const auto* b : m) {
      long miss = 0;
      std::vector<int> j = nearest_join(*a, *b, p.span_s, &miss);
      if (miss > n) continue;  // more than a second a headway to spread
      j = closed(std::move(j), p);
      if (!j.empty() && std::find(out.begin(), out.end(), j) == out.end())
        out.push_back(std::move(j));
    }
  if (out.empty()) {
    std::vector<int> nearest = relaxed_start_headways(maximisers_s, p);
    if (!nearest.empty()) out.push_back(std::move(nearest));
  }
  return out;
}

}  // namespace ecorail::fleet
