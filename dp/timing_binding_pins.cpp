#include "dp/timing_binding_pins.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <string>
#include <utility>

#include "dp/chain_lattice_search.hpp"
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
// The joint search: the lattice's first step, halved three times (to 0.125 m/s, 0.45 km/h),
// and its budget of piece solves per speed. On hb2 a first step of 2 m/s, or a finest step of
// 0.0625 m/s, found the same speeds to 1.3 kJ in 17-19 % more time.
constexpr double kFirstStep_ms = 1.0;
constexpr int kLatticeLevels = 4;
constexpr int kPieceSolvesPerSpeed = 60;

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
                                             const JourneySolve& search_solve, int threads) {
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
  auto solution_after_trying = [&]() { return after_trying(std::move(solution), evaluations, t0); };
  const auto first_part = std::find_if(solution.parts.begin(), solution.parts.end(),
                                       [&](const TimingPart& p) { return p.first_point == from; });
  if (first_part == solution.parts.end()) return solution_after_trying();

  // The stretch [from, to] splits at the pins into pieces that couple only through the pinned
  // speeds: piece k runs from pin k - 1 (or from's departure in the solution) to pin k (or to).
  // So the search's cost is a sum along a chain, each term one solve of a piece
  // (dp/chain_lattice_search.hpp).
  const std::size_t m = pins.size();
  std::vector<int> ends{from};
  ends.insert(ends.end(), pins.begin(), pins.end());
  ends.push_back(to);
  // Pieces are solved side by side (chain_lattice_minimum), so their evaluations add up here.
  std::atomic<int> piece_evaluations{0};
  auto piece_cost = [&](std::size_t k, double v_start_ms, double v_end_ms) {
    std::vector<TimingWindow> piece(w.begin() + ends[k], w.begin() + ends[k + 1] + 1);
    if (k == 0) {
      depart_at(piece.front(), first_part->departure_s);
    } else {
      piece.front().min_speed_ms = piece.front().max_speed_ms = v_start_ms;
    }
    if (k < m) piece.back().min_speed_ms = piece.back().max_speed_ms = v_end_ms;
    try {
      const TimingJourneySolution s = search_solve(piece);
      piece_evaluations += s.summary.evaluations;
      return journey_cost_J(s);
    } catch (const TimeRequestError&) {  // a state no run reaches
      return kInf;
    }
  };
  std::vector<double> lo(m), hi(m), x0(m);
  for (std::size_t k = 0; k < m; ++k) {
    const TimingWindow& asked = windows[pins[k]];
    x0[k] = solution.windows[pins[k]].speed_ms;
    lo[k] = std::max({finite(asked.min_speed_ms) ? asked.min_speed_ms : 0.0, kLowestPinned_ms});
    hi[k] = finite(asked.max_speed_ms) ? asked.max_speed_ms : kInf;
  }
  const ChainLatticeResult found =
      chain_lattice_minimum(piece_cost, x0, lo, hi, kFirstStep_ms, kLatticeLevels,
                            kPieceSolvesPerSpeed * static_cast<int>(m), threads);
  evaluations += piece_evaluations.load();
  // The journey at the cheapest lattices' speeds, in turn, until one meets every window (the
  // pieces were solved alone, without the label search).
  std::vector<std::pair<double, std::vector<double>>> met = found.lattice_bests;
  std::stable_sort(met.begin(), met.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  auto with_speeds = [&](const std::vector<double>& x) {
    std::vector<TimingWindow> v = w;
    for (std::size_t k = 0; k < m; ++k) v[pins[k]].min_speed_ms = v[pins[k]].max_speed_ms = x[k];
    return v;
  };
  CheapestTrialJourney kept = solve_cheapest_in_turn(
      met.size(), [&](std::size_t k) { return with_speeds(met[k].second); }, solve, &evaluations);
  const double label_cost = journey_cost_J(solution);
  if (!kept.met || !(journey_cost_J(*kept.solution) < label_cost)) return solution_after_trying();
  TimingJourneySolution out = std::move(*kept.solution);
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
