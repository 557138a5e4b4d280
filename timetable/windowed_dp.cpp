#include "timetable/windowed_dp.hpp"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <unordered_map>

#include "timetable/windowed_classes.hpp"

namespace ecorail::timetable {

namespace {

constexpr double kNone = -std::numeric_limits<double>::infinity();

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
  std::vector<double> cur(span + 1, kNone), next(span + 1, kNone);
  cur[0] = 0.0;
  // choice[k][t]: the last headway of the best k headways ending at t.
  std::vector<std::vector<std::int16_t>> choice(n + 1);
  for (int k = 0; k < n; ++k) {
    std::fill(next.begin(), next.end(), kNone);
    choice[k + 1].assign(span + 1, 0);
    auto& from = choice[k + 1];
    for (int t = 0; t <= span; ++t) {
      if (cur[t] == kNone || !reach.keeps(k, t)) continue;
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

HeadwayChoice maximise_windowed_chain(const FleetProblem& p, const WindowedValue& value,
                                      const std::vector<double>& penalty, long max_states) {
  check_tables(p, value);
  const int n = p.trains - 1, span = p.span_s, lo = p.any_headway_min_s();
  const int m = p.any_headway_max_s() - lo + 1;
  if (penalty.size() != static_cast<std::size_t>(m) * m)
    throw std::invalid_argument("windowed chain DP: penalty table of the wrong size");
  if (static_cast<long>(n + 1) * (span + 1) > max_states)
    throw std::length_error("windowed chain DP: (trains x span) exceeds the state limit");
  const WindowedReach reach(p);
  if (!reach.feasible()) throw std::invalid_argument("no timetable keeps the headway classes");
  HeadwayChoice out;
  if (n <= 0) return out;
  // Layer k: for every live departure time t, the best value per last headway e (kNone where
  // that e cannot end at t). Layers are kept as (t -> row) maps over the live times only; the
  // back pointers (the e before) are kept for every layer.
  using Layer = std::unordered_map<int, std::vector<double>>;
  using Back = std::unordered_map<int, std::vector<std::int16_t>>;
  std::vector<Back> back(n + 1);
  Layer cur, next;
  // Layer 1: the first headway from t = 0.
  {
    const WindowedReach::Ranges r = reach.ranges(0);
    for (const auto& [h_lo, h_hi, v] : {std::tuple{r.off_lo, r.off_hi, &value.offpeak},
                                        std::tuple{r.peak_lo, r.peak_hi, &value.peak}})
      for (int h = h_lo; h <= std::min(h_hi, span); ++h) {
        if (!reach.keeps(1, h)) continue;
        auto& row = cur[h];
        if (row.empty()) row.assign(m, kNone);
        row[h - lo] = (*v)[h - lo];
        back[1][h].assign(m, -1);
      }
  }
  std::vector<int> order(m);
  for (int k = 1; k < n; ++k) {
    next.clear();
    std::vector<int> times;
    for (const auto& kv : cur) times.push_back(kv.first);
    std::sort(times.begin(), times.end());  // a fixed order: ties resolve the same every run
    for (int t : times) {
      const std::vector<double>& row = cur[t];
      int count = 0;
      for (int e = 0; e < m; ++e)
        if (row[e] != kNone) order[count++] = e;
      std::sort(order.begin(), order.begin() + count,
                [&](int a, int b) { return row[a] > row[b] || (row[a] == row[b] && a < b); });
      out.states += count;
      const WindowedReach::Ranges r = reach.ranges(t);
      for (const auto& [h_lo, h_hi, v] : {std::tuple{r.off_lo, r.off_hi, &value.offpeak},
                                          std::tuple{r.peak_lo, r.peak_hi, &value.peak}})
        for (int h = h_lo; h <= std::min(h_hi, span - t); ++h) {
          const int t2 = t + h;
          if (!reach.keeps(k + 1, t2)) continue;
          const int e2 = h - lo;
          double best = kNone;
          int arg = -1;
          for (int i = 0; i < count; ++i) {
            const int e = order[i];
            if (row[e] <= best) break;  // penalty >= 0: no later candidate can win
            const double c = row[e] - penalty[static_cast<std::size_t>(e) * m + e2];
            if (c > best) best = c, arg = e;
          }
          auto& nrow = next[t2];
          if (nrow.empty()) {
            nrow.assign(m, kNone);
            back[k + 1][t2].assign(m, -1);
          }
          const double total = best + (*v)[e2];
          if (total > nrow[e2])
            nrow[e2] = total, back[k + 1][t2][e2] = static_cast<std::int16_t>(arg);
        }
      if (out.states > max_states)
        throw std::length_error("windowed chain DP: more than " + std::to_string(max_states) +
                                " states");
    }
    cur.swap(next);
  }
  const auto& last = cur.at(span);
  int e = static_cast<int>(std::max_element(last.begin(), last.end()) - last.begin());
  out.value = last[e];
  out.headways_s.assign(n, 0);
  int t = span;
  for (int k = n; k >= 1; --k) {
    out.headways_s[k - 1] = lo + e;
    const int before = back[k].at(t)[e];
    t -= lo + e;
    e = before;
  }
  return out;
}

}  // namespace ecorail::timetable
