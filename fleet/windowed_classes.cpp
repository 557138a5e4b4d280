#include "fleet/windowed_classes.hpp"

#include <algorithm>
#include <climits>
#include <stdexcept>

#include "fleet/windowed_dp.hpp"

namespace ecorail::fleet {

bool is_peak_headway(const std::vector<PeakWindow>& windows, int from_s, int to_s) {
  for (const PeakWindow& w : windows)
    if (from_s < w.to_s && to_s > w.from_s) return true;
  return false;
}

int offpeak_reach_s(const std::vector<PeakWindow>& windows, int t_s) {
  for (const PeakWindow& w : windows) {
    if (w.to_s <= t_s) continue;
    return w.from_s <= t_s ? 0 : w.from_s - t_s;
  }
  return INT_MAX / 4;
}

WindowedReach::Ranges WindowedReach::ranges(int t) const {
  const FleetProblem& p = *problem_;
  const int reach = offpeak_reach_s(p.peak_windows, t);
  return {p.headway_min_s, std::min(p.headway_max_s, reach),
          std::max(p.peak_headway_min_s, reach + 1), p.peak_headway_max_s};
}

WindowedReach::WindowedReach(const FleetProblem& p) : problem_(&p) {
  const int n = p.trains - 1, span = p.span_s;
  if (n < 0 || span < 0) return;
  alive_.assign(n + 1, std::vector<std::uint8_t>(span + 1, 0));
  alive_[n][span] = 1;
  // prefix[t] = number of alive states of the next layer below t.
  std::vector<int> prefix(span + 2, 0);
  auto any = [&](int lo, int hi) {
    lo = std::max(lo, 0);
    hi = std::min(hi, span);
    return lo <= hi && prefix[hi + 1] - prefix[lo] > 0;
  };
  for (int k = n - 1; k >= 0; --k) {
    for (int t = 0; t <= span; ++t) prefix[t + 1] = prefix[t] + alive_[k + 1][t];
    for (int t = 0; t <= span; ++t) {
      const Ranges r = ranges(t);
      alive_[k][t] = (any(t + r.off_lo, t + r.off_hi) || any(t + r.peak_lo, t + r.peak_hi)) ? 1 : 0;
    }
  }
  feasible_ = alive_[0][0] != 0;
}

std::pair<int, int> windowed_headway_count_range(const FleetProblem& p) {
  const int span = p.span_s;
  const int none = INT_MAX / 4;
  std::vector<int> fewest(span + 1, none), most(span + 1, -1);
  fewest[span] = 0;
  most[span] = 0;
  FleetProblem q = p;
  q.trains = 1;
  const WindowedReach ranges_only(q);
  for (int t = span - 1; t >= 0; --t) {
    const auto r = ranges_only.ranges(t);
    for (const auto& [lo, hi] : {std::pair{r.off_lo, r.off_hi}, std::pair{r.peak_lo, r.peak_hi}})
      for (int h = std::max(lo, 1); h <= hi && t + h <= span; ++h) {
        if (fewest[t + h] < none) fewest[t] = std::min(fewest[t], fewest[t + h] + 1);
        if (most[t + h] >= 0) most[t] = std::max(most[t], most[t + h] + 1);
      }
  }
  if (most[0] < 0) return {-1, -1};
  return {fewest[0], most[0]};
}

bool windowed_problem_valid(const FleetProblem& p, std::string* error) {
  auto fail = [&](const std::string& why) {
    if (error) *error = why;
    return false;
  };
  if (p.peak_headway_min_s < 1) return fail("peak_headway_min_s: expected at least 1 s");
  if (p.peak_headway_max_s < p.peak_headway_min_s)
    return fail("peak_headway_max_s: expected >= peak_headway_min_s");
  if (static_cast<long>(p.trains) * (p.span_s + 1L) > 400'000'000L)
    return fail("trains/span_s: a windowed problem of at most 4e8 (trains x span) states");
  int last_end = INT_MIN;
  for (std::size_t i = 0; i < p.peak_windows.size(); ++i) {
    const PeakWindow& w = p.peak_windows[i];
    const std::string name = "peak window " + std::to_string(i + 1) + " (" +
                             std::to_string(w.from_s) + ":" + std::to_string(w.to_s) + ")";
    if (w.to_s <= w.from_s) return fail(name + ": expected FROM < TO");
    if (w.from_s < last_end)
      return fail(name + ": expected windows in clock order that do not overlap");
    last_end = w.to_s;
  }
  if (p.trains == 1) return true;
  const WindowedReach reach(p);
  if (reach.feasible()) return true;
  // No timetable: say what each window needs and what the span can hold.
  std::string why = "no timetable of " + std::to_string(p.trains) + " trains (" +
                    std::to_string(p.trains - 1) + " headways over " + std::to_string(p.span_s) +
                    " s) keeps the headway classes:";
  for (std::size_t i = 0; i < p.peak_windows.size(); ++i) {
    const PeakWindow& w = p.peak_windows[i];
    const int from = std::max(w.from_s, 0), to = std::min(w.to_s, p.span_s);
    if (to <= from) continue;
    const int need = (to - from + p.peak_headway_max_s - 1) / p.peak_headway_max_s;
    why += " peak window " + std::to_string(i + 1) + " (" + std::to_string(w.from_s) + "-" +
           std::to_string(w.to_s) + " s) needs at least " + std::to_string(need) +
           " peak headways of at most " + std::to_string(p.peak_headway_max_s) + " s;";
  }
  const auto [fewest, most] = windowed_headway_count_range(p);
  if (fewest < 0)
    why += " no sequence of headways in their classes fills the span at all";
  else
    why += " the span holds " + std::to_string(fewest) + " to " + std::to_string(most) +
           " headways in their classes (" + std::to_string(fewest + 1) + " to " +
           std::to_string(most + 1) + " trains)";
  if (fewest >= 0 && p.trains - 1 >= fewest && p.trains - 1 <= most)
    why += ", but not exactly " + std::to_string(p.trains - 1);
  return fail(why);
}

std::string windowed_departures_problem(const FleetProblem& p, const std::vector<int>& t) {
  for (std::size_t k = 1; k < t.size(); ++k) {
    const int h = t[k] - t[k - 1];
    if (p.headway_allowed(t[k - 1], t[k])) continue;
    const bool peak = is_peak_headway(p.peak_windows, t[k - 1], t[k]);
    const int lo = peak ? p.peak_headway_min_s : p.headway_min_s;
    const int hi = peak ? p.peak_headway_max_s : p.headway_max_s;
    return "headway " + std::to_string(k) + " (" + std::to_string(t[k - 1]) + " to " +
           std::to_string(t[k]) + " s) is " + std::to_string(h) + " s, " +
           (peak ? "a peak headway (it overlaps a peak window)" : "an off-peak headway") +
           " outside [" + std::to_string(lo) + ", " + std::to_string(hi) + "] s";
  }
  return "";
}

std::vector<int> windowed_uniform_headways(const FleetProblem& p) {
  if (p.trains < 2) return {};
  // Least sum of squares for a fixed sum: the most even timetable the classes allow (convex, so
  // within each class the headways differ by as little as whole seconds and the windows'
  // edges permit; across classes peak headways as long and off-peak ones as short as allowed).
  const int lo = p.any_headway_min_s(), m = p.any_headway_max_s() - lo + 1;
  WindowedValue v;
  for (int e = 0; e < m; ++e) {
    const double h = lo + e;
    v.peak.push_back(-h * h);
    v.offpeak.push_back(-h * h);
  }
  return maximise_windowed(p, v).headways_s;
}

std::vector<int> windowed_nearest_headways(const FleetProblem& p, double peak_target_s,
                                           double offpeak_target_s) {
  if (p.trains < 2) return {};
  const int lo = p.any_headway_min_s(), m = p.any_headway_max_s() - lo + 1;
  WindowedValue v;
  for (int e = 0; e < m; ++e) {
    const double h = lo + e;
    v.peak.push_back(-(h - peak_target_s) * (h - peak_target_s));
    v.offpeak.push_back(-(h - offpeak_target_s) * (h - offpeak_target_s));
  }
  return maximise_windowed(p, v).headways_s;
}

}  // namespace ecorail::fleet
