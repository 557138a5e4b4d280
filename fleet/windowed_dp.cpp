#include "fleet/windowed_dp.hpp"

#include <algorithm>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <tuple>

#include "dp/resource_estimate.hpp"
#include "fleet/windowed_classes.hpp"

namespace ecorail::fleet {

namespace {

void check_tables(const FleetProblem& p, const WindowedValue& value) {
  const std::size_t m = p.any_headway_max_s() - p.any_headway_min_s() + 1;
  if (value.peak.size() != m || value.offpeak.size() != m)
    throw std::invalid_argument("windowed DP: value tables of the wrong size");
  if (p.any_headway_max_s() - p.any_headway_min_s() > 32000)
    throw std::invalid_argument("windowed DP: headway ranges wider than 32000 s");
}

}  // namespace

HeadwayChoice maximise_windowed(const FleetProblem& p, const WindowedValue& value,
                                long max_states) {
  check_tables(p, value);
  const int n = p.trains - 1, span = p.span_s, lo = p.any_headway_min_s();
  if (static_cast<long>(n + 1) * (span + 1) > max_states)
    throw std::length_error("windowed DP: (trains x span) exceeds the state limit");
  const WindowedReach reach(p);
  if (!reach.feasible()) throw std::invalid_argument("no timetable keeps the headway classes");
  HeadwayChoice out;
  if (n <= 0) return out;
  std::vector<double> cur(span + 1, kUnreached), next(span + 1, kUnreached);
  cur[0] = 0.0;
  // choice[k][t]: the last headway of the best k headways ending at t.
  std::vector<std::vector<std::int16_t>> choice(n + 1);
  for (int k = 0; k < n; ++k) {
    std::fill(next.begin(), next.end(), kUnreached);
    choice[k + 1].assign(span + 1, 0);
    auto& from = choice[k + 1];
    for (int t = 0; t <= span; ++t) {
      if (cur[t] == kUnreached || !reach.keeps(k, t)) continue;
      const WindowedReach::Ranges r = reach.ranges(t);
      auto relax = [&](int h_lo, int h_hi, const std::vector<double>& v) {
        h_hi = std::min(h_hi, span - t);
        for (int h = h_lo; h <= h_hi; ++h) {
          const int t2 = t + h;
          if (!reach.keeps(k + 1, t2)) continue;
          const double x = cur[t] + v[h - lo];
          if (x > next[t2]) next[t2] = x, from[t2] = static_cast<std::int16_t>(h);
        }
        if (h_hi >= h_lo) out.states += h_hi - h_lo + 1;
      };
      relax(r.off_lo, r.off_hi, value.offpeak);
      relax(r.peak_lo, r.peak_hi, value.peak);
    }
    cur.swap(next);
  }
  out.value = cur[span];
  out.headways_s.assign(n, 0);
  int t = span;
  for (int k = n; k >= 1; --k) {
    const int h = choice[k][t];
    out.headways_s[k - 1] = h;
    t -= h;
  }
  return out;
}

namespace {

// One layer of the chain DP (k headways placed): its live departure times in clock order and,
// for each, the contiguous range of last headways (as e = h - any_min) that can end there; the
// slots of a time are [offset, offset + e_hi - e_lo], so values and back pointers are flat
// arrays with no slot for an (e, t) that cannot occur.
struct ChainLayer {
  std::vector<int> times;
  std::vector<int> e_lo, e_hi;
  std::vector<std::int64_t> offset;  // times.size() + 1 entries
  std::int64_t slots() const { return offset.empty() ? 0 : offset.back(); }
  std::size_t find(int t) const {
    return static_cast<std::size_t>(std::lower_bound(times.begin(), times.end(), t) -
                                    times.begin());
  }
  std::int64_t slot(std::size_t i, int e) const { return offset[i] + (e - e_lo[i]); }
};

// The headways allowed from a departure at t: the off-peak and the peak range, each with the
// value table of its class.
template <class F>
void for_each_step(const WindowedReach& reach, const WindowedValue& value, int t, int span, F&& f) {
  const WindowedReach::Ranges r = reach.ranges(t);
  for (const auto& [h_lo, h_hi, v] : {std::tuple{r.off_lo, r.off_hi, &value.offpeak},
                                      std::tuple{r.peak_lo, r.peak_hi, &value.peak}})
    for (int h = h_lo; h <= std::min(h_hi, span - t); ++h) f(h, *v);
}

}  // namespace

HeadwayChoice maximise_windowed_chain(const FleetProblem& p, const WindowedValue& value,
                                      const std::vector<double>& penalty, long max_states) {
  check_tables(p, value);
  const int n = p.trains - 1, span = p.span_s, lo = p.any_headway_min_s();
  const int m = p.any_headway_max_s() - lo + 1;
  if (penalty.size() != static_cast<std::size_t>(m) * m)
    throw std::invalid_argument("windowed chain DP: penalty table of the wrong size");
  const WindowedReach reach(p);
  if (!reach.feasible()) throw std::invalid_argument("no timetable keeps the headway classes");
  HeadwayChoice out;
  if (n <= 0) return out;

  // 1. The layers' layout: the states reachable forward from t = 0 that can still reach the
  // span (WindowedReach), with each time's range of last headways.
  std::vector<ChainLayer> layers(n + 1);
  layers[0].times = {0};
  layers[0].e_lo = {0};
  layers[0].e_hi = {-1};
  layers[0].offset = {0, 0};
  std::vector<int> e_lo(span + 1, m), e_hi(span + 1, -1);
  for (int k = 0; k < n; ++k) {
    std::vector<int> touched;
    for (int t : layers[k].times)
      for_each_step(reach, value, t, span, [&](int h, const std::vector<double>&) {
        const int t2 = t + h;
        if (!reach.keeps(k + 1, t2)) return;
        if (e_hi[t2] < 0) touched.push_back(t2);
        e_lo[t2] = std::min(e_lo[t2], h - lo);
        e_hi[t2] = std::max(e_hi[t2], h - lo);
      });
    std::sort(touched.begin(), touched.end());
    ChainLayer& next = layers[k + 1];
    next.times = touched;
    next.offset.assign(1, 0);
    for (int t2 : touched) {
      next.e_lo.push_back(e_lo[t2]);
      next.e_hi.push_back(e_hi[t2]);
      next.offset.push_back(next.offset.back() + e_hi[t2] - e_lo[t2] + 1);
      e_lo[t2] = m, e_hi[t2] = -1;
    }
    out.states += next.slots();
    if (out.states > max_states)
      throw std::length_error("windowed chain DP: more than " + std::to_string(max_states) +
                              " states");
    if (2.0 * static_cast<double>(out.states) > 0.5 * dp::memory_limit_bytes())
      throw std::length_error("windowed chain DP: its " + std::to_string(out.states) +
                              "+ states need more than half the memory this process can have");
  }
  if (layers[n].times.empty() || layers[n].times.back() != span)
    throw std::logic_error("windowed chain DP: the span is not reached");

  // 2. Values layer by layer (two at a time); back pointers (the e before) for every layer.
  std::vector<std::vector<std::int16_t>> back(n + 1);
  std::vector<double> cur, next;
  std::vector<int> order(m);
  std::vector<double> row_value(m);
  std::vector<std::int64_t> where(span + 1, -1);  // index of a time in the next layer
  for (int k = 0; k < n; ++k) {
    const ChainLayer& from = layers[k];
    const ChainLayer& to = layers[k + 1];
    next.assign(static_cast<std::size_t>(to.slots()), kUnreached);
    back[k + 1].assign(static_cast<std::size_t>(to.slots()), -1);
    for (std::size_t j = 0; j < to.times.size(); ++j) where[to.times[j]] = j;
    for (std::size_t i = 0; i < from.times.size(); ++i) {
      const int t = from.times[i];
      // The candidates e of this state by falling value (ties: the smaller e first).
      int count = 0;
      if (k == 0) {
        order[count++] = -1;  // no headway before the first
        row_value[0] = 0.0;
      } else {
        for (int e = from.e_lo[i]; e <= from.e_hi[i]; ++e) {
          const double x = cur[static_cast<std::size_t>(from.slot(i, e))];
          if (x != kUnreached) order[count++] = e;
        }
        const std::int64_t base = from.offset[i] - from.e_lo[i];
        std::sort(order.begin(), order.begin() + count, [&](int a, int b) {
          const double va = cur[base + a], vb = cur[base + b];
          return va > vb || (va == vb && a < b);
        });
        for (int c = 0; c < count; ++c) row_value[c] = cur[base + order[c]];
      }
      if (count == 0) continue;
      for_each_step(reach, value, t, span, [&](int h, const std::vector<double>& v) {
        const int t2 = t + h;
        if (!reach.keeps(k + 1, t2)) return;
        const int e2 = h - lo;
        double best = kUnreached;
        int arg = -1;
        for (int c = 0; c < count; ++c) {
          if (row_value[c] <= best) break;  // penalty >= 0: no later candidate can win
          const double x =
              k == 0 ? row_value[c]
                     : row_value[c] - penalty[static_cast<std::size_t>(order[c]) * m + e2];
          if (x > best) best = x, arg = order[c];
        }
        const std::size_t j = static_cast<std::size_t>(to.slot(where[t2], e2));
        const double total = best + v[e2];
        if (total > next[j]) next[j] = total, back[k + 1][j] = static_cast<std::int16_t>(arg);
      });
    }
    for (int t2 : to.times) where[t2] = -1;
    cur.swap(next);
  }

  // 3. The best last headway at the span, then back along the pointers.
  const ChainLayer& last = layers[n];
  const std::size_t i_end = last.find(span);
  int e = last.e_lo[i_end];
  for (int x = last.e_lo[i_end]; x <= last.e_hi[i_end]; ++x)
    if (cur[last.slot(i_end, x)] > cur[last.slot(i_end, e)]) e = x;
  out.value = cur[last.slot(i_end, e)];
  out.headways_s.assign(n, 0);
  int t = span;
  for (int k = n; k >= 1; --k) {
    out.headways_s[k - 1] = lo + e;
    const int before = back[k][layers[k].slot(layers[k].find(t), e)];
    t -= lo + e;
    e = before;
  }
  return out;
}

}  // namespace ecorail::fleet
