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
constexpr int kPinSteps = 8;
// A time bracket's ends are bisected to the golden section's tolerance, in at most kEdgeSteps
// checks each.
constexpr int kEdgeSteps = 12;

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
                                         const JourneySolve& trial_solve,
                                         const JourneyRefused& refused) {
  const int n = static_cast<int>(windows.size());
  // Each point to pin, and whether its speed (not its time) is searched: one time at a free
  // speed only where the plain search misses a window or leaves the point's part to the label
  // search, whose energy is a heuristic's (a part from one pinned state to another through a
  // point at one time: 45 % above a witness run, and the journey with that point's speed
  // pinned below its witness).
  auto by_label_search = [&](const TimingJourneySolution& s, int i) {
    return std::any_of(s.parts.begin(), s.parts.end(), [&](const TimingPart& p) {
      return p.by_label_search && p.first_point < i && i < p.last_point;
    });
  };
  std::vector<std::pair<int, bool>> pins;
  for (int i = 1; i + 1 < n; ++i) {
    if (asks_one_speed_at_a_free_time(windows[i])) pins.push_back({i, false});
    if ((!plain.windows_met || by_label_search(plain, i)) &&
        asks_one_time_at_a_free_speed(windows[i])) {
      pins.push_back({i, true});
    }
  }
  if (pins.empty() || static_cast<int>(pins.size()) > kMaxSpeedPins ||
      windows.back().position_m - windows.front().position_m > kSpeedPinReach_m) {
    return plain;
  }
  const auto t0 = std::chrono::steady_clock::now();
  int evaluations = 0;
  // plain, its evaluations and wall time counting the pins' solves too (they were spent).
  auto plain_after_trying = [&]() { return after_trying(std::move(plain), evaluations, t0); };
  std::vector<TimingWindow> w = windows;
  std::optional<TimingJourneySolution> pinned;  // the whole journey with every point pinned so far
  for (std::size_t next = 0; next < pins.size(); ++next) {
    // (Named copies, not a structured binding: the lambdas below capture them.)
    const int i = pins[next].first;
    const bool by_speed = pins[next].second;
    const TimingJourneySolution& reference = pinned ? *pinned : plain;
    // The part that holds i, solved alone from its departure in the reference: the other
    // parts do not change with i's time or speed.
    const auto part = std::find_if(reference.parts.begin(), reference.parts.end(),
                                   [&](const TimingPart& p) { return p.last_point > i; });
    if (part == reference.parts.end() || part->first_point >= i) return plain_after_trying();
    std::vector<TimingWindow> sub(w.begin() + part->first_point, w.begin() + part->last_point + 1);
    depart_at(sub.front(), part->departure_s);
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
    if (!(finite(lo) && finite(hi) && hi > lo)) return plain_after_trying();
    std::vector<std::pair<double, double>> met;  // (cost, x) of each trial that met its windows
    auto trial_at = [&](double x) {
      std::vector<TimingWindow> trial = sub;
      trial[at] = pinned_at(x);
      return trial;
    };
    auto cost_at = [&](double x) {
      try {
        const TimingJourneySolution s = trial_solve(trial_at(x));
        evaluations += s.summary.evaluations;
        const double c = journey_cost_J(s);
        if (finite(c)) met.push_back({c, x});
        return c;
      } catch (const TimeRequestError&) {  // a state no run reaches (or too slow)
        return kInf;
      }
    };
    // A time's bracket narrowed to the times some run can meet: [lo, hi] spans the times between
    // the points either side, and most of it can be out of reach (a point 750 m after one at
    // 61.1 s is passed no earlier than 96.7 s, and one 68.5 s before the arrival at 209.5 s no
    // later than 141.0 s): the golden section's first trials were all refused there and it
    // settled 5 s from the witness's time. Each end is bisected towards the reference run's own
    // time, which a run meets, on the refusal before any search (flat-out runs, no grid).
    const double tolerance = by_speed ? kPinSpeedTolerance_ms : kPinTimeTolerance_s;
    double a = lo, b = hi;
    if (!by_speed && finite(x_ref) && x_ref > lo && x_ref < hi) {
      for (double* end : {&a, &b}) {
        double out = *end, in = x_ref;
        if (!refused(trial_at(out))) continue;
        for (int k = 0; k < kEdgeSteps && std::abs(in - out) > tolerance; ++k) {
          const double m = 0.5 * (in + out);
          (refused(trial_at(m)) ? out : in) = m;
        }
        *end = in;
      }
    }
    golden_section_minimum(cost_at, a, b, tolerance, kPinSteps, true);
    if (finite(x_ref) && x_ref > lo && x_ref < hi) cost_at(x_ref);  // the run's own
    // The journey on the asked grid at the cheapest trial's value; the trials' grid is coarser,
    // and a value met there can be missed here (a time at 1 813.9 m of seed 71's journey 27 at
    // the default grid: the trials around it alternate between met and missed), so the next
    // cheapest trials are solved in turn, up to kFinalTries in all, until one meets every
    // window. When none does, the cheapest trial's journey is kept and the next pin searched
    // from it (a journey with two time points may need both pinned).
    std::sort(met.begin(), met.end());
    CheapestTrialJourney kept = solve_cheapest_in_turn(
        met.size(),
        [&](std::size_t k) {
          std::vector<TimingWindow> journey = w;
          journey[i] = pinned_at(met[k].second);
          return journey;
        },
        solve, &evaluations);
    if (!kept.solution) return plain_after_trying();
    w[i] = pinned_at(met[kept.index].second);
    pinned = std::move(kept.solution);
    // A pin splits its part in two, and one of them may now be the label search's (a point
    // pinned after another point at one time): that point is pinned too, within the limit.
    for (int k = 1; k + 1 < n && static_cast<int>(pins.size()) < kMaxSpeedPins; ++k) {
      const bool known = std::any_of(pins.begin(), pins.end(),
                                     [&](const std::pair<int, bool>& p) { return p.first == k; });
      if (!known && by_label_search(*pinned, k) && asks_one_time_at_a_free_speed(w[k])) {
        pins.push_back({k, true});
      }
    }
  }
  const double plain_cost = journey_cost_J(plain);
  if (!(journey_cost_J(*pinned) < plain_cost)) return plain_after_trying();
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
                                       units::J_to_kJ(plain_cost - journey_cost_J(out)))
                               .c_str()
                         : "every window holds, where the plain search missed one"));
  out.journey.warnings = out.summary.warnings;
  return out;
}

}  // namespace ecorail::dp::timing
