#include "fleet/fleet_problem.hpp"

#include <algorithm>
#include <cmath>

#include "fleet/windowed_classes.hpp"

namespace ecorail::fleet {

bool FleetProblem::IsValid(std::string* error) const {
  auto fail = [&](const std::string& why) {
    if (error) *error = why;
    return false;
  };
  if (trains < 1 || trains > 100000) return fail("trains: expected 1 to 100000");
  if (headway_min_s < 1) return fail("headway_min_s: expected at least 1 s");
  if (headway_max_s < headway_min_s) return fail("headway_max_s: expected >= headway_min_s");
  if (span_s < 0) return fail("span_s: expected >= 0");
  if (!(std::isfinite(trip_time_s) && trip_time_s > 0.0))
    return fail("trip_time_s: expected a positive, finite time");
  if (!(std::isfinite(dwell_min_s) && dwell_min_s >= 0.0))
    return fail("dwell_min_s: expected >= 0");
  if (!(std::isfinite(dwell_max_s) && dwell_max_s >= dwell_min_s))
    return fail("dwell_max_s: expected >= dwell_min_s");
  const long n = trains - 1;
  if (n == 0 && span_s != 0) return fail("span_s: one train has no headway, so the span is 0");
  if (windowed()) return windowed_problem_valid(*this, error);
  if (n > 0 && (n * headway_min_s > span_s || n * headway_max_s < span_s)) {
    return fail("span_s: " + std::to_string(n) + " headways in [" + std::to_string(headway_min_s) +
                ", " + std::to_string(headway_max_s) + "] s sum to " +
                std::to_string(n * headway_min_s) + " to " + std::to_string(n * headway_max_s) +
                " s, not " + std::to_string(span_s) + " s");
  }
  return true;
}

bool FleetProblem::headway_allowed(int from_s, int to_s) const {
  const int h = to_s - from_s;
  if (windowed() && is_peak_headway(peak_windows, from_s, to_s))
    return h >= peak_headway_min_s && h <= peak_headway_max_s;
  return h >= headway_min_s && h <= headway_max_s;
}

int FleetProblem::any_headway_min_s() const {
  return windowed() ? std::min(headway_min_s, peak_headway_min_s) : headway_min_s;
}

int FleetProblem::any_headway_max_s() const {
  return windowed() ? std::max(headway_max_s, peak_headway_max_s) : headway_max_s;
}

energy::FleetLimits limits_of(const FleetProblem& p) {
  return {p.trains, p.span_s, p.any_headway_min_s(), p.any_headway_max_s(), p.windowed() ? 2 : 1};
}

std::vector<int> departures_from_headways(const std::vector<int>& headways_s) {
  std::vector<int> t{0};
  for (int h : headways_s) t.push_back(t.back() + h);
  return t;
}

std::vector<int> headways_from_departures(const std::vector<int>& departures_s) {
  std::vector<int> h;
  for (std::size_t k = 1; k < departures_s.size(); ++k)
    h.push_back(departures_s[k] - departures_s[k - 1]);
  return h;
}

std::string departures_problem(const FleetProblem& p, const std::vector<int>& t) {
  if (static_cast<int>(t.size()) != p.trains)
    return std::to_string(t.size()) + " departures, expected " + std::to_string(p.trains);
  if (t.empty()) return "";
  if (t.front() != 0) return "the first departure is at " + std::to_string(t.front()) + " s, not 0";
  if (t.back() != p.span_s)
    return "the last departure is at " + std::to_string(t.back()) + " s, not the span " +
           std::to_string(p.span_s) + " s (headways sum to " + std::to_string(t.back()) + " s)";
  if (p.windowed()) return windowed_departures_problem(p, t);
  for (std::size_t k = 1; k < t.size(); ++k) {
    const int h = t[k] - t[k - 1];
    if (h < p.headway_min_s || h > p.headway_max_s)
      return "headway " + std::to_string(k) + " is " + std::to_string(h) + " s, outside [" +
             std::to_string(p.headway_min_s) + ", " + std::to_string(p.headway_max_s) + "] s";
  }
  return "";
}

std::vector<int> uniform_headways(const FleetProblem& p) {
  if (p.windowed()) return windowed_uniform_headways(p);
  const int n = p.trains - 1;
  std::vector<int> h;
  if (n <= 0) return h;
  const int base = p.span_s / n, extra = p.span_s % n;
  for (int k = 0; k < n; ++k) h.push_back(base + (k < extra ? 1 : 0));
  return h;
}

}  // namespace ecorail::fleet
