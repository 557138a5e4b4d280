#include "dp/timing_speed_pins.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <string>
#include <utility>

#include "dp/golden_section.hpp"
#include "dp/text_format.hpp"
#include "dp/timing_journey_part.hpp"
#include "physics/units.hpp"

namespace ecorail::dp::timing {

namespace {

// Journeys with more such points, or longer, are left to the plain search: each point costs
// kPinSteps + 3 solves of its part and one of the whole journey.
constexpr int kMaxSpeedPins = 4;
constexpr double kSpeedPinReach_m = 10000.0;
// The golden section on a point's time: to half a second; on its speed: to 0.05 m/s, from no
// lower than a crawl; at most kPinSteps steps.
constexpr double kPinTimeTolerance_s = 0.5;
constexpr double kPinSpeedTolerance_ms = 0.05;
constexpr double kLowestPinned_ms = 0.5;
constexpr int kPinSteps = 8;

// The journey's energy cost by its objective; +inf when a window is missed.
double cost_of(const TimingJourneySolution& s) {
  if (!s.windows_met || !s.summary.IsSolutionUsable()) return kInf;
  double cost = 0.0;
  for (const JourneySection& section : s.journey.sections) cost += section.run.cost_J;
  return cost;
}

}  // namespace

bool asks_one_speed_at_a_free_time(const TimingWindow& w) {
  return !w.is_stop() && finite(w.min_speed_ms) && w.min_speed_ms == w.max_speed_ms &&
         w.min_speed_ms > 0.0 && !(finite(w.earliest_s) && w.earliest_s == w.latest_s);
}

bool asks_one_time_at_a_free_speed(const TimingWindow& w) {
  return !w.is_stop() && finite(w.earliest_s) && w.earliest_s == w.latest_s &&
         !(finite(w.min_speed_ms) && w.min_speed_ms == w.max_speed_ms);
}

TimingJourneySolution with_speeds_pinned(const std::vector<TimingWindow>& windows,
                                         TimingJourneySolution plain, const JourneySolve& solve,
                                         const JourneySolve& trial_solve) {
  const int n = static_cast<int>(windows.size());
  // Each point to pin, and whether its speed (not its time) is searched: one time at a free
  // speed only where the plain search misses a window.
  std::vector<std::pair<int, bool>> pins;
  for (int i = 1; i + 1 < n; ++i) {
    if (asks_one_speed_at_a_free_time(windows[i])) pins.push_back({i, false});
    if (!plain.windows_met && asks_one_time_at_a_free_speed(windows[i])) pins.push_back({i, true});
  }
  if (pins.empty() || static_cast<int>(pins.size()) > kMaxSpeedPins ||
      windows.back().position_m - windows.front().position_m > kSpeedPinReach_m) {
    return plain;
  }
  const auto t0 = std::chrono::steady_clock::now();
  std::vector<TimingWindow> w = windows;
  std::optional<TimingJourneySolution> pinned;  // the whole journey with every point pinned so far
  int evaluations = 0;
  for (const auto& pin : pins) {
    // (Named copies, not a structured binding: the lambdas below capture them.)
    const int i = pin.first;
    const bool by_speed = pin.second;
    const TimingJourneySolution& reference = pinned ? *pinned : plain;
    // The part that holds i, solved alone from its departure in the reference: the other
    // parts do not change with i's time or speed.
    const auto part = std::find_if(reference.parts.begin(), reference.parts.end(),
                                   [&](const TimingPart& p) { return p.last_point > i; });
    if (part == reference.parts.end() || part->first_point >= i) return plain;
    std::vector<TimingWindow> sub(w.begin() + part->first_point, w.begin() + part->last_point + 1);
    sub.front().earliest_s = part->departure_s;
    sub.front().latest_s = std::max(sub.front().latest_s, part->departure_s);
    const int at = i - part->first_point;
    // The pinned window for x (a time, or a speed), and where x is searched: a time between
    // the reference run's times at the points either side, a speed within half the reference
    // run's speed there either side.
    auto pinned_at = [&](double x) {
      return by_speed ? TimingWindow{w[i].position_m, w[i].earliest_s, w[i].latest_s, x, x}
                      : TimingWindow{w[i].position_m, x, x, w[i].min_speed_ms, w[i].max_speed_ms};
    };
    const double x_ref = by_speed ? reference.windows[i].speed_ms : reference.windows[i].time_s;
    const double lo = by_speed ? std::max({w[i].min_speed_ms, 0.5 * x_ref, kLowestPinned_ms})
                               : std::max(w[i].earliest_s, reference.windows[i - 1].time_s);
    const double hi = by_speed ? std::min(w[i].max_speed_ms, 1.5 * x_ref)
                               : std::min(w[i].latest_s, reference.windows[i + 1].time_s);
    if (!(finite(lo) && finite(hi) && hi > lo)) return plain;
    double best_cost = kInf, best_x = NAN;
    auto cost_at = [&](double x) {
      std::vector<TimingWindow> trial = sub;
      trial[at] = pinned_at(x);
      try {
        const TimingJourneySolution s = trial_solve(trial);
        evaluations += s.summary.evaluations;
        const double c = cost_of(s);
        if (c < best_cost) best_cost = c, best_x = x;
        return c;
      } catch (const TimeRequestError&) {  // a state no run reaches (or too slow)
        return kInf;
      }
    };
    golden_section_minimum(cost_at, lo, hi, by_speed ? kPinSpeedTolerance_ms : kPinTimeTolerance_s,
                           kPinSteps, true);
    if (finite(x_ref) && x_ref > lo && x_ref < hi) cost_at(x_ref);  // the run's own
    if (!finite(best_cost)) return plain;
    w[i] = pinned_at(best_x);
    try {
      pinned = solve(w);
    } catch (const TimeRequestError&) {
      return plain;
    }
    evaluations += pinned->summary.evaluations;
  }
  const double plain_cost = cost_of(plain);
  if (!(cost_of(*pinned) < plain_cost)) return plain;
  TimingJourneySolution out = std::move(*pinned);
  std::string where;
  for (const auto& [i, by_speed] : pins) {
    WindowResult& r = out.windows[i];
    r.window = windows[i];
    if (by_speed) {
      r.binds = {"earliest", "latest"};
      where += format_text("%s%s at %.2f km/h", where.empty() ? "" : ", ",
                           point_name(i, windows[i]).c_str(), units::ms_to_kmh(r.speed_ms));
    } else {
      r.binds = {"min_speed", "max_speed"};
      where += format_text("%s%s at %.1f s", where.empty() ? "" : ", ",
                           point_name(i, windows[i]).c_str(), r.time_s);
    }
  }
  const double extra_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  out.summary.evaluations = plain.summary.evaluations + evaluations;
  out.summary.total_wall_s = plain.summary.total_wall_s + extra_s;
  out.journey.total_wall_s = out.summary.total_wall_s;
  out.summary.warnings.push_back(format_text(
      "zero-width windows pinned: %s, each at the time or speed searched for it (golden "
      "section over solves of its part); %s",
      where.c_str(),
      finite(plain_cost) ? format_text("%.1f kJ less than the plain search",
                                       units::J_to_kJ(plain_cost - cost_of(out)))
                               .c_str()
                         : "every window holds, where the plain search missed one"));
  out.journey.warnings = out.summary.warnings;
  return out;
}

}  // namespace ecorail::dp::timing
