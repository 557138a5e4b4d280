#include "timetable/search_starts.hpp"

#include <algorithm>
#include <numeric>
#include <stdexcept>

namespace ecorail::timetable {

std::vector<int> repair_to_span(std::vector<int> h, const FleetProblem& p) {
  const int n = p.trains - 1;
  if (static_cast<int>(h.size()) != n)
    throw std::invalid_argument("repair_to_span: one headway per pair of trains expected");
  if (static_cast<long>(n) * p.headway_min_s > p.span_s ||
      static_cast<long>(n) * p.headway_max_s < p.span_s)
    throw std::invalid_argument("repair_to_span: no headways in range fill the span");
  for (int& x : h) x = std::clamp(x, p.headway_min_s, p.headway_max_s);
  long excess = std::accumulate(h.begin(), h.end(), 0L) - p.span_s;
  // Each pass moves every headway that can still move by one second, the longest first when
  // shortening (the shortest first when lengthening), until the sum is the span.
  std::vector<int> order(n);
  while (excess != 0) {
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(),
                     [&](int a, int b) { return excess > 0 ? h[a] > h[b] : h[a] < h[b]; });
    for (int k : order) {
      if (excess == 0) break;
      if (excess > 0 && h[k] > p.headway_min_s) --h[k], --excess;
      if (excess < 0 && h[k] < p.headway_max_s) ++h[k], ++excess;
    }
  }
  return h;
}

}  // namespace ecorail::timetable
