#include "fleet/headway_optimiser.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <stdexcept>

#include "fleet/headway_dp.hpp"
#include "fleet/search_support.hpp"
#include "fleet/windowed_dp.hpp"

namespace ecorail::fleet {

namespace {

using energy::FleetBalance;
using energy::FleetEnergyModel;
using energy::MicroJoules;
using energy::SearchPlan;
using energy::to_joules;
using Clock = SearchClock;

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

// The headway values of a table over [any min, any max] for both classes of a windowed problem.
WindowedValue both_classes(const std::vector<double>& value) {
  return {value, value};
}

bool past(Clock::time_point t0, double limit_s) {
  return limit_s > 0.0 && seconds_since(t0) > limit_s;
}

// The exact DP of a model whose used energy decomposes over headways.
HeadwayOptimiserResult solve_decomposed(const FleetEnergyModel& model, const FleetProblem& p,
                                        const energy::HeadwayDecomposition& d) {
  HeadwayOptimiserResult out;
  HeadwayOptimiserSummary& s = out.summary;
  const bool chain = static_cast<bool>(d.penalty_J);
  HeadwayChoice choice;
  if (p.windowed()) {
    // Peak windows: the same values, the class of each headway from the clock.
    const int lo = p.any_headway_min_s(), m = p.any_headway_max_s() - lo + 1;
    std::vector<double> value(m);
    for (int e = 0; e < m; ++e) value[e] = d.value_J(lo + e);
    if (!chain) {
      choice = maximise_windowed(p, both_classes(value));
      s.method = "exact windowed DP over (train, clock time) (" + d.what + ")";
    } else {
      std::vector<double> penalty(static_cast<std::size_t>(m) * m);
      for (int a = 0; a < m; ++a)
        for (int b = 0; b < m; ++b)
          penalty[static_cast<std::size_t>(a) * m + b] = d.penalty_J(lo + a, lo + b);
      choice = maximise_windowed_chain(p, both_classes(value), penalty);
      s.method = "exact windowed chain DP over (train, clock time, last headway) (" + d.what + ")";
    }
  } else {
    const int lo = p.headway_min_s, m = p.headway_max_s - lo + 1;
    std::vector<double> value(m);
    for (int e = 0; e < m; ++e) value[e] = d.value_J(lo + e);
    if (!chain) {
      choice = maximise_separable(domain_of(p), value);
      s.method = "exact DP over the headway sum (" + d.what + ")";
    } else {
      std::vector<double> penalty(static_cast<std::size_t>(m) * m);
      for (int e = 0; e < m; ++e)
        for (int e2 = 0; e2 < m; ++e2)
          penalty[static_cast<std::size_t>(e) * m + e2] = d.penalty_J(lo + e, lo + e2);
      choice = maximise_chain(domain_of(p), value, penalty);
      s.method = "exact chain DP over the headway sum (" + d.what + ")";
    }
  }
  out.headways_s = choice.headways_s;
  out.evaluation = model.evaluate(departures_from_headways(out.headways_s));
  s.exact = true;
  s.dp_states = choice.states;
  s.used_regen_J = out.evaluation.total.used_regen_J;
  s.start_used_J = s.used_regen_J;
  s.bound_used_regen_J = s.used_regen_J;
  s.substation_J = out.evaluation.total.substation_J();
  s.gap_fraction = 0.0;
  return out;
}

struct RunResult {
  std::vector<int> departures;
  MicroJoules substation = 0;
  long moves = 0;
  bool stopped = false;
};

// Simulated annealing on the departures of trains 1..N-2, minimising the substation energy.
RunResult anneal(FleetBalance& balance, const FleetProblem& p, const SearchPlan& plan,
                 std::vector<int> t, std::uint64_t seed, std::uint64_t run, long moves,
                 Clock::time_point t0, double limit_s) {
  const auto draw = [&](std::uint64_t move, std::uint64_t k) {
    return counter_draw(seed, run, move, k, plan.draw_salt);
  };
  RunResult out;
  balance.place_all(t);
  out.departures = t;
  out.substation = balance.substation();
  const int n = p.trains;
  if (n < 3 || moves == 0) return out;
  // Temperature: from the mean size of a few proposals' changes down by 1000x.
  double mean = 0.0;
  int samples = 0;
  for (int i = 0; i < plan.temperature_samples; ++i) {
    const int k = 1 + static_cast<int>(draw(i, 0) % (n - 2));
    auto [lo, hi] = feasible_range(p, t, k);
    if (plan.samples_within_move_window) lo = std::max(lo, t[k] - 30), hi = std::min(hi, t[k] + 30);
    if (hi <= lo) continue;
    const int d = lo + static_cast<int>(draw(i, 1) % (hi - lo + 1));
    if (!allowed(p, t, k, d)) continue;
    const int back = t[k];
    mean += std::fabs(static_cast<double>(balance.move(k, d)));
    balance.move(k, back);
    ++samples;
  }
  const double t_start = samples > 0 ? std::max(1.0, mean / samples) : 1.0;
  const double cool = std::pow(1e-3, 1.0 / static_cast<double>(moves));
  double temperature = t_start;
  MicroJoules current = balance.substation();
  const long check_mask = plan.time_check_every - 1;
  for (long m = 0; m < moves; ++m, temperature *= cool) {
    if ((m & check_mask) == 0 && past(t0, limit_s)) {
      out.stopped = true;
      break;
    }
    const std::uint64_t counter = m + plan.draw_offset;
    const int k = 1 + static_cast<int>(draw(counter, 0) % (n - 2));
    auto [lo, hi] = feasible_range(p, t, k);
    lo = std::max(lo, t[k] - 30);
    hi = std::min(hi, t[k] + 30);
    if (hi <= lo) continue;
    int d = lo + static_cast<int>(draw(counter, 1) % (hi - lo));
    if (d >= t[k]) ++d;  // never the current departure
    if (d > hi || !allowed(p, t, k, d)) continue;
    const MicroJoules delta = balance.move(k, d);  // < 0: better
    ++out.moves;
    const bool accept = delta <= 0 || uniform01(draw(counter, 2)) <
                                          std::exp(-static_cast<double>(delta) / temperature);
    if (!accept) {
      balance.move(k, t[k]);
      continue;
    }
    t[k] = d;
    current += delta;
    if (current < out.substation) out.substation = current, out.departures = t;
  }
  return out;
}

// Tries every departure within +-window for every train in turn, keeping the best, until a sweep
// changes nothing (at most `sweeps`); the time limit stops it between trains (*stopped set; the
// timetable so far is kept).
long polish(FleetBalance& balance, const FleetProblem& p, std::vector<int>& t, int window,
            int sweeps, Clock::time_point t0, double limit_s, bool* stopped) {
  long moves = 0;
  balance.place_all(t);
  for (int sweep = 0; sweep < sweeps && !*stopped; ++sweep) {
    bool improved = false;
    for (int k = 1; k + 1 < p.trains; ++k) {
      if (past(t0, limit_s)) {
        *stopped = true;
        break;
      }
      auto [lo, hi] = feasible_range(p, t, k);
      lo = std::max(lo, t[k] - window);
      hi = std::min(hi, t[k] + window);
      const int start = t[k];
      MicroJoules best = balance.substation();
      int best_d = start;
      for (int d = lo; d <= hi; ++d) {
        if (d == start || !allowed(p, t, k, d)) continue;
        balance.move(k, d);
        ++moves;
        if (balance.substation() < best) best = balance.substation(), best_d = d;
      }
      balance.move(k, best_d);
      improved |= best_d != start;
      t[k] = best_d;
    }
    if (!improved) break;
  }
  return moves;
}

// The grid step of a polish stage (the model's own when 0).
double polish_step(const SearchPlan::Polish& stage, double anneal_step_s) {
  return stage.step_s < 0.0 ? anneal_step_s : stage.step_s;
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
  if (!(std::isfinite(gap_fraction) && gap_fraction >= 0.0 && gap_fraction < 1.0))
    return fail("gap_fraction: expected a fraction in [0, 1) of the substation energy");
  energy::EnergyModelOptions grid;
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
  std::string out = buf;
  if (termination != Termination::CONVERGENCE && !message.empty()) out += "; " + message;
  return out;
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

void settle_termination(HeadwayOptimiserSummary& s, double gap_tolerance, bool unsolved) {
  char buf[256];
  if (unsolved) {
    s.termination = Termination::FAILURE;
    s.message = "the model found no solution at some instants of the result";
  } else if (std::isfinite(s.gap_fraction) && s.gap_fraction <= gap_tolerance) {
    s.termination = Termination::CONVERGENCE;
    s.message.clear();
  } else {
    s.termination = Termination::NO_CONVERGENCE;
    if (!std::isfinite(s.gap_fraction)) {
      std::snprintf(buf, sizeof buf, "%s, and no bound proves a gap",
                    s.time_limit_reached ? "the time limit stopped the search"
                                         : "the search ended at its move budget");
    } else {
      std::snprintf(buf, sizeof buf,
                    "%s with a proven gap of %.4f %% of the substation energy (above the gap "
                    "tolerance %.4f %%)",
                    s.time_limit_reached ? "the time limit stopped the search"
                                         : "the search ended at its move budget",
                    100.0 * s.gap_fraction, 100.0 * gap_tolerance);
    }
    s.message = buf;
  }
}

HeadwayOptimiserResult optimise_headways(const FleetEnergyModel& model, const FleetProblem& p,
                                         const HeadwayOptimiserOptions& options) {
  const auto t0 = Clock::now();
  std::string why;
  if (!options.IsValid(&why)) throw std::invalid_argument(why);
  if (!p.IsValid(&why)) throw std::invalid_argument(why);
  if (model.limits().trains != p.trains || model.limits().span_s != p.span_s)
    throw std::invalid_argument("the model was built for another fleet than the problem's");
  const auto report = [&](const std::string& stage, double best, double bound) {
    if (options.progress) options.progress({seconds_since(t0), best, bound, stage});
  };

  if (const auto decomposition = model.headway_decomposition()) {
    HeadwayOptimiserResult out = solve_decomposed(model, p, *decomposition);
    settle_termination(out.summary, options.gap_fraction, false);
    out.summary.wall_s = seconds_since(t0);
    return out;
  }
  HeadwayOptimiserResult out;
  HeadwayOptimiserSummary& s = out.summary;
  const SearchPlan plan = model.search_plan();
  const int threads = options.threads > 0 ? options.threads : omp_get_max_threads();
  // The annealing's coarser grid: a move touches far fewer bins.
  const std::unique_ptr<FleetEnergyModel> coarse = model.on_grid(options.anneal_step_s);
  if (!coarse->make_balance(1))
    throw std::invalid_argument("the " + std::string(model.name()) +
                                " model has neither a headway decomposition nor a balance");

  // Starts: the exact optimum of the two-train approximation (with peak windows: the windowed
  // DP's, the same values for both classes), and the uniform timetable.
  const int lo = p.any_headway_min_s(), hi = p.any_headway_max_s();
  const std::vector<double> pair =
      (plan.two_train_values_on_search_grid ? *coarse : model).two_train_values_J(lo, hi, threads);
  report("two-train approximation", 0.0, NAN);
  std::vector<std::vector<int>> starts;
  if (p.windowed())
    starts.push_back(departures_from_headways(maximise_windowed(p, both_classes(pair)).headways_s));
  else
    starts.push_back(departures_from_headways(maximise_separable(domain_of(p), pair).headways_s));
  starts.push_back(departures_from_headways(uniform_headways(p)));
  if (plan.price_starts) {
    for (const auto& t : starts)
      s.start_used_J = std::max(s.start_used_J, model.evaluate(t).total.used_regen_J);
  }
  report("starts", s.start_used_J, NAN);

  // Annealing: every start, restarts times; the model's share of the time limit.
  const int per_start =
      plan.run_without_restarts ? std::max(1, options.restarts) : options.restarts;
  const long moves = options.restarts == 0 ? 0 : options.moves_per_run;
  const int runs = static_cast<int>(starts.size()) * per_start;
  const double anneal_limit = plan.anneal_share_of_time_limit * options.time_limit_s;
  std::vector<RunResult> results(runs);
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads)
  for (int r = 0; r < runs; ++r) {
    const std::unique_ptr<FleetBalance> balance = coarse->make_balance(1);
    results[r] = anneal(*balance, p, plan, starts[r % starts.size()], options.seed, r, moves, t0,
                        anneal_limit);
  }
  std::vector<std::vector<int>> candidates;
  std::size_t best_run = 0;
  for (std::size_t r = 0; r < results.size(); ++r) {
    s.moves += results[r].moves;
    s.time_limit_reached |= results[r].stopped;
    if (results[r].substation < results[best_run].substation) best_run = r;
  }
  if (plan.polish_every_run) {
    for (const auto& r : results) candidates.push_back(r.departures);
    if (candidates.empty()) candidates = starts;
  } else {
    candidates.push_back(results[best_run].departures);
  }
  report("annealing done", s.start_used_J, NAN);

  // Polish each candidate through the plan's stages (candidates side by side, each stage's
  // balance on one thread; one candidate: its balance on every thread). The best wins (ties:
  // the first), so the outcome does not depend on which thread ran what.
  std::vector<std::unique_ptr<FleetEnergyModel>> grids;
  for (const SearchPlan::Polish& stage : plan.polish) {
    const double step = polish_step(stage, options.anneal_step_s);
    grids.push_back(stage.step_s == 0.0 ? nullptr : model.on_grid(step));
  }
  const int n_candidates = static_cast<int>(candidates.size());
  const int balance_threads = n_candidates == 1 ? threads : 1;
  std::vector<MicroJoules> polished(n_candidates, 0);
  std::vector<long> polish_moves(n_candidates, 0);
  std::vector<char> stopped(n_candidates, 0);
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads) if (n_candidates > 1)
  for (int c = 0; c < n_candidates; ++c) {
    bool stop = false;
    for (std::size_t i = 0; i < plan.polish.size(); ++i) {
      const SearchPlan::Polish& stage = plan.polish[i];
      const FleetEnergyModel& grid = grids[i] ? *grids[i] : model;
      if (stop || (stage.skip_on_search_grid &&
                   grid.options().ticks_per_second() == coarse->options().ticks_per_second()))
        continue;
      const int window = stage.window_s < 0 ? options.polish_window_s
                                            : std::min(stage.window_s, options.polish_window_s);
      const std::unique_ptr<FleetBalance> balance = grid.make_balance(balance_threads);
      polish_moves[c] +=
          polish(*balance, p, candidates[c], window, stage.sweeps, t0, options.time_limit_s, &stop);
      polished[c] = balance->substation();
    }
    stopped[c] = stop;
  }
  std::size_t best_c = 0;
  for (int c = 0; c < n_candidates; ++c) {
    s.moves += polish_moves[c];
    s.time_limit_reached |= stopped[c] != 0;
    if (polished[c] < polished[best_c]) best_c = c;
  }
  const std::vector<int>& best = candidates[best_c];
  report("polish", 0.0, NAN);

  const energy::FleetLowerBound bound = model.lower_bound();
  out.headways_s = headways_from_departures(best);
  out.evaluation = model.evaluate(best);
  s.method = "annealing (" + std::to_string(runs) + " runs) and polish" + plan.method_note +
             (bound.name.empty() ? "" : ", " + bound.name);
  s.used_regen_J = out.evaluation.used_regen_J();
  s.substation_J = out.evaluation.total.substation_J();
  s.bound_used_regen_J = bound.used_regen_J;
  s.bound_substation_J = bound.substation_J;
  s.curtailed_traction_J =
      out.evaluation.network ? out.evaluation.network->curtailed_traction_J : 0.0;
  s.gap_fraction = bound.exists() ? model.gap_fraction(out.evaluation, bound) : NAN;
  s.pair_sum_J = model.pair_sum_J(best);
  settle_termination(s, options.gap_fraction,
                     out.evaluation.network && out.evaluation.network->unsolved_instants > 0);
  s.wall_s = seconds_since(t0);
  report("done", s.used_regen_J, s.bound_used_regen_J);
  return out;
}

}  // namespace ecorail::fleet
