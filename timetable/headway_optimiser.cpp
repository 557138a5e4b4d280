#include "timetable/headway_optimiser.hpp"
#include "timetable/search_support.hpp"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>

#include "timetable/headway_dp.hpp"
#include "timetable/network_optimiser.hpp"
#include "timetable/pair_bound.hpp"
#include "timetable/search_starts.hpp"
#include "timetable/window_bound.hpp"
#include "timetable/windowed_dp.hpp"

namespace ecorail::timetable {

namespace {

using Clock = SearchClock;

// Counter-based random numbers (search_support.hpp).
std::uint64_t draw(std::uint64_t seed, std::uint64_t run, std::uint64_t move, std::uint64_t k) {
  return counter_draw(seed, run, move, k);
}

HeadwayDomain domain_of(const FleetProblem& p) {
  return {p.trains - 1, p.headway_min_s, p.headway_max_s, p.span_s};
}

// The departure range of train k (0 < k < N-1) given its neighbours (with peak windows: the
// range of any class; allowed() then checks the classes of both headways).
std::pair<int, int> feasible_range(const FleetProblem& p, const std::vector<int>& t, int k) {
  const int lo = std::max(t[k - 1] + p.any_headway_min_s(), t[k + 1] - p.any_headway_max_s());
  const int hi = std::min(t[k - 1] + p.any_headway_max_s(), t[k + 1] - p.any_headway_min_s());
  return {lo, hi};
}

bool allowed(const FleetProblem& p, const std::vector<int>& t, int k, int d) {
  return !p.windowed() || (p.headway_allowed(t[k - 1], d) && p.headway_allowed(d, t[k + 1]));
}

// The headway values of a table over [lo, lo + m) for both classes of a windowed problem.
WindowedValue both_classes(const FleetProblem& p, const std::function<double(int)>& value) {
  WindowedValue v;
  for (int h = p.any_headway_min_s(); h <= p.any_headway_max_s(); ++h) {
    v.peak.push_back(value(h));
    v.offpeak.push_back(value(h));
  }
  return v;
}

struct RunResult {
  std::vector<int> departures;
  MicroJoules used = 0;
  long moves = 0;
  bool stopped = false;
};

// Simulated annealing on the departures of trains 1..N-2, maximising used energy.
RunResult anneal(const FleetModels& coarse, std::vector<int> t, std::uint64_t seed,
                 std::uint64_t run, long moves, const Clock::time_point t0, double limit_s) {
  const FleetProblem& p = coarse.problem();
  RunResult out;
  auto balance = coarse.make_balance();
  balance->place_all(t);
  out.departures = t;
  out.used = balance->used();
  const int n = p.trains;
  if (n < 3) return out;
  // Temperature: from the mean size of a few proposals' changes down by 1000x.
  double mean = 0.0;
  int samples = 0;
  for (int i = 0; i < 64; ++i) {
    const int k = 1 + static_cast<int>(draw(seed, run, i, 0) % (n - 2));
    const auto [lo, hi] = feasible_range(p, t, k);
    if (hi <= lo) continue;
    const int d = lo + static_cast<int>(draw(seed, run, i, 1) % (hi - lo + 1));
    if (!allowed(p, t, k, d)) continue;
    const int back = t[k];
    mean += std::fabs(static_cast<double>(balance->move(k, d)));
    balance->move(k, back);
    ++samples;
  }
  const double t_start = samples > 0 ? std::max(1.0, mean / samples) : 1.0;
  const double cool = std::pow(1e-3, 1.0 / std::max(1L, moves));
  double temperature = t_start;
  MicroJoules used = balance->used();
  for (long m = 0; m < moves; ++m, temperature *= cool) {
    if (limit_s > 0.0 && (m & 1023) == 0 && seconds_since(t0) > limit_s) {
      out.stopped = true;
      break;
    }
    const int k = 1 + static_cast<int>(draw(seed, run, m, 0) % (n - 2));
    auto [lo, hi] = feasible_range(p, t, k);
    lo = std::max(lo, t[k] - 30);
    hi = std::min(hi, t[k] + 30);
    if (hi <= lo) continue;
    int d = lo + static_cast<int>(draw(seed, run, m, 1) % (hi - lo));
    if (d >= t[k]) ++d;  // never the current departure
    if (d > hi || !allowed(p, t, k, d)) continue;
    const MicroJoules delta = balance->move(k, d);
    const bool accept = delta >= 0 || uniform01(draw(seed, run, m, 2)) <
                                          std::exp(static_cast<double>(delta) / temperature);
    ++out.moves;
    if (!accept) {
      balance->move(k, t[k]);
      continue;
    }
    t[k] = d;
    used += delta;
    if (used > out.used) out.used = used, out.departures = t;
  }
  return out;
}

// Tries every departure within +-window for every train in turn, keeping the best, until a
// sweep changes nothing.
long polish(PowerBalance& balance, const FleetProblem& p, std::vector<int>& t, int window) {
  long moves = 0;
  for (int sweep = 0; sweep < 50; ++sweep) {
    bool improved = false;
    for (int k = 1; k + 1 < p.trains; ++k) {
      auto [lo, hi] = feasible_range(p, t, k);
      lo = std::max(lo, t[k] - window);
      hi = std::min(hi, t[k] + window);
      const int start = t[k];
      MicroJoules best = balance.used();
      int best_d = start;
      for (int d = lo; d <= hi; ++d) {
        if (d == start || !allowed(p, t, k, d)) continue;
        balance.move(k, d);
        ++moves;
        if (balance.used() > best) best = balance.used(), best_d = d;
      }
      balance.move(k, best_d);
      if (best_d != start) improved = true;
      t[k] = best_d;
    }
    if (!improved) break;
  }
  return moves;
}

}  // namespace

bool HeadwayOptimiserOptions::IsValid(std::string* error) const {
  auto fail = [&](const std::string& why) {
    if (error) *error = why;
    return false;
  };
  if (restarts < 0 || restarts > 1000) return fail("restarts: expected 0 to 1000");
  if (moves_per_run < 0) return fail("moves_per_run: expected >= 0");
  if (polish_window_s < 0 || polish_window_s > 10000)
    return fail("polish_window_s: expected 0 to 10000 s");
  if (!(std::isfinite(time_limit_s) && time_limit_s >= 0.0))
    return fail("time_limit_s: expected a finite time >= 0 (0: no limit)");
  EnergyModelOptions grid;
  grid.time_step_s = anneal_step_s;
  if (!grid.IsValid(nullptr)) return fail("anneal_step_s: expected a step that divides one second");
  if (threads < 0 || threads > 1024) return fail("threads: expected 0 (default) to 1024");
  return true;
}

std::string HeadwayOptimiserSummary::BriefReport() const {
  char buf[512];
  if (std::isfinite(bound_substation_J)) {
    std::snprintf(buf, sizeof buf,
                  "%s: %s, used regen %.1f kJ, substation %.1f kJ, bound %.1f kJ, gap %.4f %% of "
                  "substation energy, %.2f s",
                  std::string(termination_name(termination)).c_str(), method.c_str(),
                  used_regen_J / 1e3, substation_J / 1e3, bound_substation_J / 1e3,
                  100.0 * gap_fraction, wall_s);
  } else if (std::isfinite(bound_used_regen_J)) {
    std::snprintf(buf, sizeof buf,
                  "%s: %s, used regen %.1f kJ, bound %.1f kJ, gap %.4f %% of substation energy "
                  "%.1f kJ, %.2f s",
                  std::string(termination_name(termination)).c_str(), method.c_str(),
                  used_regen_J / 1e3, bound_used_regen_J / 1e3, 100.0 * gap_fraction,
                  substation_J / 1e3, wall_s);
  } else {
    std::snprintf(buf, sizeof buf, "%s: %s, used regen %.1f kJ, substation %.1f kJ, %.2f s",
                  std::string(termination_name(termination)).c_str(), method.c_str(),
                  used_regen_J / 1e3, substation_J / 1e3, wall_s);
  }
  return buf;
}

std::string HeadwayOptimiserSummary::FullReport() const {
  std::string out = BriefReport() + "\n";
  char buf[512];
  std::snprintf(buf, sizeof buf,
                "  exact: %s\n  best start (used regen): %.1f kJ\n  moves evaluated: %ld\n"
                "  DP states: %ld\n  time limit reached: %s\n",
                exact ? "yes" : "no", start_used_J / 1e3, moves, dp_states,
                time_limit_reached ? "yes" : "no");
  out += buf;
  if (pair_sum_J > 0.0) {
    std::snprintf(buf, sizeof buf,
                  "  pair sum of the result: %.1f kJ (%.4f %% of substation energy above the "
                  "used energy: no pair-based bound can close that part of the gap)\n",
                  pair_sum_J / 1e3, 100.0 * (pair_sum_J - used_regen_J) / substation_J);
    out += buf;
  }
  if (!message.empty()) out += "  " + message + "\n";
  return out;
}

HeadwayOptimiserResult optimise_headways(const FleetModels& models,
                                         const HeadwayOptimiserOptions& options) {
  if (models.options().model == EnergyModel::Network)
    return optimise_network_headways(models, options);  // timetable/network_optimiser.hpp
  const auto t0 = Clock::now();
  std::string why;
  if (!options.IsValid(&why)) throw std::invalid_argument(why);
  const FleetProblem& p = models.problem();
  const EnergyModelOptions& eo = models.options();
  const HeadwayDomain dom = domain_of(p);
  const int lo = p.headway_min_s, m = p.headway_max_s - p.headway_min_s + 1;
  HeadwayOptimiserResult out;
  HeadwayOptimiserSummary& s = out.summary;
  auto report = [&](const std::string& stage, double best, double bound) {
    if (options.progress) options.progress({seconds_since(t0), best, bound, stage});
  };

  if (eo.model == EnergyModel::Overlap) {
    const OverlapModel& ov = models.overlap();
    std::vector<double> value(m);
    HeadwayChoice choice;
    if (p.windowed()) {
      // Peak windows: the same values, the class of each headway from the clock.
      const int any_lo = p.any_headway_min_s(), any_m = p.any_headway_max_s() - any_lo + 1;
      if (eo.overlap == OverlapVariant::Ahead) {
        choice =
            maximise_windowed(p, both_classes(p, [&](int h) { return ov.used_from_ahead_J(h); }));
        s.method = "exact windowed DP over (train, clock time) (overlap, train ahead)";
      } else {
        std::vector<double> penalty(static_cast<std::size_t>(any_m) * any_m);
        for (int a = 0; a < any_m; ++a)
          for (int b = 0; b < any_m; ++b)
            penalty[static_cast<std::size_t>(a) * any_m + b] =
                ov.double_count_J(any_lo + a, any_lo + b);
        choice = maximise_windowed_chain(
            p,
            both_classes(p,
                         [&](int h) { return ov.used_from_ahead_J(h) + ov.used_from_behind_J(h); }),
            penalty);
        s.method =
            "exact windowed chain DP over (train, clock time, last headway) (overlap, either "
            "neighbour)";
      }
    } else if (eo.overlap == OverlapVariant::Ahead) {
      for (int e = 0; e < m; ++e) value[e] = ov.used_from_ahead_J(lo + e);
      choice = maximise_separable(dom, value);
      s.method = "exact DP over the headway sum (overlap, train ahead)";
    } else {
      std::vector<double> penalty(static_cast<std::size_t>(m) * m);
      for (int e = 0; e < m; ++e)
        value[e] = ov.used_from_ahead_J(lo + e) + ov.used_from_behind_J(lo + e);
      for (int e = 0; e < m; ++e)
        for (int e2 = 0; e2 < m; ++e2)
          penalty[static_cast<std::size_t>(e) * m + e2] = ov.double_count_J(lo + e, lo + e2);
      choice = maximise_chain(dom, value, penalty);
      s.method = "exact chain DP over the headway sum (overlap, either neighbour)";
    }
    out.headways_s = choice.headways_s;
    out.evaluation = models.evaluate(departures_from_headways(out.headways_s));
    s.exact = true;
    s.dp_states = choice.states;
    s.used_regen_J = out.evaluation.total.used_regen_J;
    s.start_used_J = s.used_regen_J;
    s.bound_used_regen_J = s.used_regen_J;
    s.substation_J = out.evaluation.total.substation_J();
    s.gap_fraction = 0.0;
    s.termination = Termination::CONVERGENCE;
    s.wall_s = seconds_since(t0);
    return out;
  }

  // Power-flow and sections. Starts: the exact optimum of the two-train approximation, and the
  // uniform timetable.
  const PowerProfile& fine = models.profile();
  std::vector<double> pair(m, 0.0);
  {
    PowerBalance two({&fine, &fine}, p.headway_max_s + models.trip().arrival_s() + 2.0);
    for (int e = 0; e < m; ++e) {
      two.place_all({0, lo + e});
      pair[e] = to_joules(two.used());
    }
  }
  report("two-train approximation", 0.0, NAN);
  std::vector<std::vector<int>> starts;
  if (p.windowed()) {
    PowerBalance two({&fine, &fine}, p.any_headway_max_s() + models.trip().arrival_s() + 2.0);
    starts.push_back(
        departures_from_headways(maximise_windowed(p, both_classes(p,
                                                                   [&](int h) {
                                                                     two.place_all({0, h});
                                                                     return to_joules(two.used());
                                                                   }))
                                     .headways_s));
  } else {
    starts.push_back(departures_from_headways(maximise_separable(dom, pair).headways_s));
  }
  starts.push_back(departures_from_headways(uniform_headways(p)));
  // Hook: the window bound (window_bound.hpp), when asked for; the maximiser of its relaxed
  // problem, moved onto the span, is one more start (search_starts.hpp).
  WindowBound window;
  if (options.window_bound && eo.model == EnergyModel::PowerFlow && !p.windowed()) {
    report("window bound", 0.0, NAN);
    WindowBoundOptions wo;
    wo.threads = options.threads > 0 ? options.threads : omp_get_max_threads();
    window = window_used_regen_bound(fine, p, wo);
    if (window.applicable)
      starts.push_back(departures_from_headways(repair_to_span(window.best_maximiser, p)));
  }
  MicroJoules start_best = 0;
  {
    auto balance = models.make_balance();
    for (const auto& t : starts) {
      balance->place_all(t);
      start_best = std::max(start_best, balance->used());
    }
  }
  s.start_used_J = to_joules(start_best);
  report("starts", s.start_used_J, NAN);

  // Annealing on the coarser grid of anneal_step_s (or the model's step if coarser): a move
  // touches far fewer bins; the polish below ends on the model's own grid.
  EnergyModelOptions coarse_options = eo;
  coarse_options.time_step_s = std::max(eo.time_step_s, options.anneal_step_s);
  const FleetModels coarse(models.trip(), p, coarse_options);
  const int runs = static_cast<int>(starts.size()) * options.restarts;
  std::vector<RunResult> results(runs);
  const int threads = options.threads > 0 ? options.threads : omp_get_max_threads();
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads)
  for (int r = 0; r < runs; ++r) {
    results[r] = anneal(coarse, starts[r % starts.size()], options.seed, r, options.moves_per_run,
                        t0, options.time_limit_s);
  }
  // Polish every annealed result (the starts themselves when there is no annealing): first on
  // a 0.1 s grid over the whole window, then on the model's grid within +-3 s, the candidates
  // side by side. The best wins (ties: the first), so the outcome does not depend on which
  // thread ran what.
  std::vector<std::vector<int>> candidates;
  for (const auto& r : results) {
    candidates.push_back(r.departures);
    s.moves += r.moves;
    s.time_limit_reached |= r.stopped;
  }
  if (candidates.empty()) candidates = starts;
  report("annealing done", s.start_used_J, NAN);
  EnergyModelOptions mid_options = eo;
  mid_options.time_step_s = std::max(eo.time_step_s, 0.1);
  const FleetModels mid(models.trip(), p, mid_options);
  std::vector<MicroJoules> polished(candidates.size(), 0);
  std::vector<long> polish_moves(candidates.size(), 0);
  const int n_candidates = static_cast<int>(candidates.size());
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads)
  for (int c = 0; c < n_candidates; ++c) {
    auto& t = candidates[c];
    auto coarse_balance = mid.make_balance();
    coarse_balance->place_all(t);
    polish_moves[c] += polish(*coarse_balance, p, t, options.polish_window_s);
    coarse_balance.reset();
    auto balance = models.make_balance();
    balance->place_all(t);
    polish_moves[c] += polish(*balance, p, t, std::min(3, options.polish_window_s));
    polished[c] = balance->used();
  }
  std::size_t best_c = 0;
  for (std::size_t c = 0; c < candidates.size(); ++c) {
    s.moves += polish_moves[c];
    if (polished[c] > polished[best_c]) best_c = c;
  }
  const std::vector<int>& best = candidates[best_c];
  report("polish", to_joules(polished[best_c]), NAN);
  // With peak windows the bound relaxes the classes to one range covering both (still a bound).
  FleetProblem relaxed = p;
  relaxed.peak_windows.clear();
  relaxed.headway_min_s = p.any_headway_min_s();
  relaxed.headway_max_s = p.any_headway_max_s();
  const PairBound bound = used_regen_bound(fine, relaxed);
  out.headways_s = headways_from_departures(best);
  out.evaluation = models.evaluate(best);
  s.method = "annealing (" + std::to_string(runs) + " runs) and polish, pair bound";
  s.used_regen_J = out.evaluation.total.used_regen_J;
  s.substation_J = out.evaluation.total.substation_J();
  // No timetable uses more than is regenerated, nor more than is drawn.
  s.bound_used_regen_J =
      std::min({bound.bound_used_J, out.evaluation.total.regen_J, out.evaluation.total.traction_J});
  // Hook: the window bound computed before the annealing (window_bound.hpp).
  if (window.applicable && window.bound_used_J < s.bound_used_regen_J) {
    s.bound_used_regen_J = window.bound_used_J;
    s.method += ", window bound";
  }
  s.gap_fraction = (s.bound_used_regen_J - s.used_regen_J) / s.substation_J;
  s.pair_sum_J = pair_sum_J(fine, best);
  s.termination = s.time_limit_reached ? Termination::NO_CONVERGENCE : Termination::CONVERGENCE;
  if (s.time_limit_reached) s.message = "the time limit stopped the annealing early";
  s.wall_s = seconds_since(t0);
  report("done", s.used_regen_J, s.bound_used_regen_J);
  return out;
}

}  // namespace ecorail::timetable
