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

std::vector<int> relaxed_start_headways(const std::vector<std::vector<int>>& maximisers_s,
                                        const FleetProblem& p) {
  const std::size_t n = static_cast<std::size_t>(std::max(0, p.trains - 1));
  std::vector<const std::vector<int>*> usable;
  for (const auto& m : maximisers_s)
    if (m.size() == n && n > 0) usable.push_back(&m);
  if (usable.empty()) return {};
  // The best join of a prefix of a and the suffix of b over every ordered pair (a = b: the
  // maximiser itself): the joined sum nearest the span.
  long best_miss = -1;
  std::vector<int> best;
  for (const auto* a : usable) {
    for (const auto* b : usable) {
      // sum(a[0..k)) + sum(b[k..n)) for k = 0..n.
      long joined = std::accumulate(b->begin(), b->end(), 0L);
      for (std::size_t k = 0; k <= n; ++k) {
        const long miss = std::labs(joined - p.span_s);
        if (best_miss < 0 || miss < best_miss) {
          best_miss = miss;
          best.assign(a->begin(), a->begin() + static_cast<long>(k));
          best.insert(best.end(), b->begin() + static_cast<long>(k), b->end());
        }
        if (k < n) joined += (*a)[k] - (*b)[k];
      }
    }
  }
  for (int& h : best) h = std::clamp(h, p.headway_min_s, p.headway_max_s);
  if (!spread_to_span(best, p.span_s, p.headway_min_s, p.headway_max_s)) return {};
  return best;
}

}  // namespace ecorail::fleet
