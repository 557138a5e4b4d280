#include "dp/timing_binding_pins.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <string>
#include <utility>

#include "dp/nelder_mead.hpp"
#include "dp/text_format.hpp"
#include "dp/timing_journey_part.hpp"
#include "physics/units.hpp"

namespace ecorail::dp::timing {

namespace {

// A label run that passes a point within this of a time bound binds it (the run is moved onto
// its windows to a bucket's width, 0.5-1 s, by the label search).
constexpr double kBindingSlack_s = 1.0;
// Parts with more such points are left as the label search ran them: the joint search's cost
// grows with the number of speeds.
constexpr int kMaxBindingPins = 6;
// The joint search: the simplex's first steps, its tolerance, its budget per speed.
constexpr double kFirstStep_ms = 0.5;
constexpr double kSpeedTolerance_ms = 0.05;
constexpr int kEvaluationsPerSpeed = 20;
constexpr double kLowestPinned_ms = 0.5;
// At most this many of the cheapest trials are solved on the asked grid.
constexpr std::size_t kFinalTries = 3;

// The time bound a label run passing at t_s binds, NaN when none.
double binding_bound(const TimingWindow& w, double t_s) {
  if (finite(w.earliest_s) && std::abs(t_s - w.earliest_s) <= kBindingSlack_s) return w.earliest_s;
  if (finite(w.latest_s) && std::abs(t_s - w.latest_s) <= kBindingSlack_s) return w.latest_s;
  return NAN;
}

TimingWindow pinned_state(const TimingWindow& w, double t_s, double v_ms) {
  return TimingWindow{w.position_m, t_s, t_s, v_ms, v_ms};
}

}  // namespace

TimingJourneySolution with_label_runs_pinned(const std::vector<TimingWindow>& windows,
                                             TimingJourneySolution solution,
                                             const JourneySolve& solve,
                                             const JourneySolve& search_solve) {
  const int n = static_cast<int>(windows.size());
  if (static_cast<int>(solution.windows.size()) != n || !solution.windows_met) return solution;
  // The journey as solved: every moving point a part starts from that the journey does not pin
  // itself was pinned to its state by the speed pins, and stays so.
  std::vector<TimingWindow> w = windows;
  for (const TimingPart& part : solution.parts) {
    const int i = part.first_point;
    const TimingWindow& asked = windows[i];
    const bool pinned_as_asked =
        asked.earliest_s == asked.latest_s && asked.min_speed_ms == asked.max_speed_ms;
    if (i > 0 && i + 1 < n && !asked.is_stop() && !pinned_as_asked) {
      w[i] = pinned_state(windows[i], solution.windows[i].time_s, solution.windows[i].speed_ms);
    }
  }
  // The points to pin, and the stretch of the journey their speeds change: from the first
  // label part's first point to the last one's last point.
  std::vector<int> pins;
  std::vector<bool> at_earliest;  // per pin: the bound pinned is its earliest (else its latest)
  int from = n, to = -1;
  for (const TimingPart& part : solution.parts) {
    if (!part.by_label_search) continue;
    for (int i = part.first_point + 1; i < part.last_point; ++i) {
      const double bound = binding_bound(windows[i], solution.windows[i].time_s);
      if (!finite(bound) || !(solution.windows[i].speed_ms > 0.0)) continue;
      w[i] = pinned_state(windows[i], bound, solution.windows[i].speed_ms);
      pins.push_back(i);
      at_earliest.push_back(bound == windows[i].earliest_s);
      from = std::min(from, part.first_point);
      to = std::max(to, part.last_point);
    }
  }
  if (pins.empty() || static_cast<int>(pins.size()) > kMaxBindingPins) return solution;

  const auto t0 = std::chrono::steady_clock::now();
  int evaluations = 0;
  auto spent_s = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  };
  auto solution_after_trying = [&]() {
    solution.summary.evaluations += evaluations;
    solution.summary.total_wall_s += spent_s();
    solution.journey.total_wall_s = solution.summary.total_wall_s;
    return std::move(solution);
  };
  const auto first_part = std::find_if(solution.parts.begin(), solution.parts.end(),
                                       [&](const TimingPart& p) { return p.first_point == from; });
  if (first_part == solution.parts.end()) return solution_after_trying();

  // One trial: the stretch [from, to] from its departure in the solution, the pins at speeds x.
  std::vector<TimingWindow> sub(w.begin() + from, w.begin() + to + 1);
  sub.front().earliest_s = first_part->departure_s;
  sub.front().latest_s = std::max(sub.front().latest_s, first_part->departure_s);
  auto with_speeds = [&](std::vector<TimingWindow> v, int offset, const std::vector<double>& x) {
    for (std::size_t k = 0; k < pins.size(); ++k) {
      TimingWindow& p = v[pins[k] - offset];
      p.min_speed_ms = p.max_speed_ms = x[k];
    }
    return v;
  };
  std::vector<double> lo(pins.size()), hi(pins.size()), x0(pins.size()), step(pins.size());
  for (std::size_t k = 0; k < pins.size(); ++k) {
    const TimingWindow& asked = windows[pins[k]];
    x0[k] = solution.windows[pins[k]].speed_ms;
    lo[k] = std::max({finite(asked.min_speed_ms) ? asked.min_speed_ms : 0.0, kLowestPinned_ms});
    hi[k] = finite(asked.max_speed_ms) ? asked.max_speed_ms : kInf;
    step[k] = x0[k] - kFirstStep_ms >= lo[k] ? -kFirstStep_ms : kFirstStep_ms;
  }
  std::vector<std::pair<double, std::vector<double>>> met;  // (cost, speeds) of met trials
  auto cost_at = [&](const std::vector<double>& x) {
    for (std::size_t k = 0; k < x.size(); ++k) {
      if (!(x[k] >= lo[k] && x[k] <= hi[k])) return kInf;
    }
    try {
      const TimingJourneySolution s = search_solve(with_speeds(sub, from, x));
      evaluations += s.summary.evaluations;
      const double c = journey_cost_J(s);
      if (finite(c)) met.push_back({c, x});
      return c;
    } catch (const TimeRequestError&) {  // a state no run reaches
      return kInf;
    }
  };
  nelder_mead_minimum(cost_at, x0, step, kSpeedTolerance_ms,
                      kEvaluationsPerSpeed * static_cast<int>(pins.size()));
  // The journey at the cheapest trials' speeds, in turn, until one meets every window (the
  // trials solve the stretch alone, without the label search).
  std::stable_sort(met.begin(), met.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  std::optional<TimingJourneySolution> best;
  for (std::size_t k = 0; k < met.size() && k < kFinalTries && !best; ++k) {
    try {
      TimingJourneySolution s = solve(with_speeds(w, 0, met[k].second));
      evaluations += s.summary.evaluations;
      if (finite(journey_cost_J(s))) best = std::move(s);
    } catch (const TimeRequestError&) {
    }
  }
  const double label_cost = journey_cost_J(solution);
  if (!best || !(journey_cost_J(*best) < label_cost)) return solution_after_trying();
  TimingJourneySolution out = std::move(*best);
  for (int i = 0; i < n; ++i) out.windows[i].window = windows[i];  // reported as asked
  std::string where;
  for (std::size_t k = 0; k < pins.size(); ++k) {
    const int i = pins[k];
    WindowResult& r = out.windows[i];
    r.binds = {at_earliest[k] ? "earliest" : "latest"};
    where += format_text("%s%s at %.1f s, %.2f km/h", where.empty() ? "" : ", ",
                         point_name(i, windows[i]).c_str(), r.time_s, units::ms_to_kmh(r.speed_ms));
  }
  out.summary.evaluations = solution.summary.evaluations + evaluations;
  out.summary.total_wall_s = solution.summary.total_wall_s + spent_s();
  out.journey.total_wall_s = out.summary.total_wall_s;
  out.summary.warnings.push_back(format_text(
      "the part's price searches missed a window; the time-expanded label search's run is pinned "
      "where it binds a time: %s (the speeds searched jointly over "
      "solves between the pinned states); %.1f kJ less than the label search's run, feasible, "
      "possibly not the least energy",
      where.c_str(), units::J_to_kJ(label_cost - journey_cost_J(out))));
  out.journey.warnings = out.summary.warnings;
  return out;
}

}  // namespace ecorail::dp::timing
