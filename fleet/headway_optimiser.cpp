#include "fleet/headway_optimiser.hpp"

#include <omp.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <future>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>

#include "fleet/headway_dp.hpp"
#include "fleet/headway_moves.hpp"
#include "fleet/regime_start.hpp"
#include "fleet/relaxed_start.hpp"
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

// With a time limit, the share of it the bound may take (docs/fleet.md, `--time-limit S`).
constexpr double kBoundShareOfTimeLimit = 0.5;

HeadwayDomain domain_of(const FleetProblem& p) {
  return {p.trains - 1, p.headway_min_s, p.headway_max_s, p.span_s};
}

// The headway values of a table over [any min, any max] for both classes of a windowed problem.
WindowedValue both_classes(const std::vector<double>& value) {
  return {value, value};
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
  if (rounds < 0 || rounds > 1000000) return fail("rounds: expected 0 to 1000000");
  if (!(reanneal_temperature > 0.0 && reanneal_temperature <= 1.0))
    return fail("reanneal_temperature: expected a fraction in (0, 1]");
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
                "  DP states: %ld\n  further rounds: %d\n  time limit reached: %s\n",
                exact ? "yes" : "no", start_used_J / 1e3, moves, dp_states, rounds,
                time_limit_reached ? "yes" : "no");
  out += buf;
  if (pair_sum_J > 0.0) {
    std::snprintf(buf, sizeof buf,
                  "  pair sum of the result: %.1f kJ (%.4f %% of substation energy above the "
                  "used energy: no pair-based bound can close that part of the gap)\n",
                  pair_sum_J / 1e3, 100.0 * (pair_sum_J - used_regen_J) / substation_J);
    out += buf;
  }
  if (std::isfinite(given_start_used_J)) {
    std::snprintf(buf, sizeof buf, "  given timetable (used regen): %.1f kJ\n",
                  given_start_used_J / 1e3);
    out += buf;
  }
  if (!exact_part.empty()) {
    std::snprintf(buf, sizeof buf,
                  "  exact search on part of the domain: no timetable with %s uses more than "
                  "%.1f kJ\n",
                  exact_part.c_str(), exact_part_used_J / 1e3);
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
  for (const std::vector<int>& given : options.given_starts_s)
    if (const std::string bad = departures_problem(p, given); !bad.empty())
      throw std::invalid_argument("given start: " + bad);
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

  // The bound holds for every timetable of the problem, whatever the search finds, and the
  // search never reads it (only the progress line and the summary do). Without a time limit and
  // on more than one thread it is taken beside the search, on a thread of its own from the
  // start: its DP and the search's starts and annealing share the cores, and 2.1's default run
  // ends in 57 s instead of 66 s (median of three, docs/fleet.md). With a time limit it is taken
  // first and may take until half of it, on every thread (then the best bound it has, named
  // so): beside the search it would get half the cores for that share of the limit. The
  // relaxation's maximisers (a start) may take up to 0.6 of it all. share_past(share, from_s):
  // with a time limit, past from_s plus `share` of what the limit leaves after it.
  const auto share_past = [&](double share, double from_s = 0.0) {
    return [&options, t0, share, from_s] {
      return options.time_limit_s > 0.0 &&
             past(t0, from_s + share * std::max(0.0, options.time_limit_s - from_s));
    };
  };
  // The bound and the regime start take seconds on a long day: the stop they ask also ticks the
  // progress line, twice a second, from the calling thread only (their parallel loops ask it
  // from the others too).
  double last_tick_s = 0.0;
  const auto ticking = [&](const std::string& stage, double bound_J, std::function<bool()> stop) {
    return [&, stage, bound_J, stop = std::move(stop)] {
      if (options.progress && omp_get_thread_num() == 0 && seconds_since(t0) >= last_tick_s + 0.5) {
        last_tick_s = seconds_since(t0);
        report(stage, 0.0, bound_J);
      }
      return stop();
    };
  };
  report("bound", 0.0, NAN);
  std::optional<energy::FleetLowerBound> bound_taken;
  // Set when the search throws (an error, a cancel): the bound stops at its next check.
  std::atomic<bool> leaving{false};
  std::future<energy::FleetLowerBound> bound_beside;
  if (threads > 1 && !(options.time_limit_s > 0.0)) {
    bound_beside = std::async(std::launch::async, [&model, &leaving, threads] {
      omp_set_num_threads(threads);  // a thread of its own starts from OpenMP's defaults
      return model.lower_bound([&leaving] { return leaving.load(); });
    });
  } else {
    bound_taken = model.lower_bound(ticking("bound", NAN, share_past(kBoundShareOfTimeLimit)));
  }
  // Declared after the bound's future, so destroyed before it: the future's destructor then
  // waits for a bound told to stop.
  const struct LeaveGuard {
    std::atomic<bool>& leaving;
    ~LeaveGuard() { leaving = true; }
  } leave_guard{leaving};
  // The bound's used energy once it is known (NaN before), for the progress line.
  const auto bound_used = [&]() {
    if (!bound_taken && bound_beside.valid() &&
        bound_beside.wait_for(std::chrono::seconds(0)) == std::future_status::ready)
      bound_taken = bound_beside.get();
    return bound_taken ? bound_taken->used_regen_J : NAN;
  };

  // Starts: the DP over the trip's periodic regimes (regime_start.hpp), the join of the bound
  // relaxation's maximisers (relaxed_start.hpp; one headway class, where every headway may lie
  // in the core in which the relaxation's window terms are exact), the exact
  // optimum of the two-train approximation (with peak windows: the windowed DP's, the same
  // values for both classes), and the uniform timetable.
  const int lo = p.any_headway_min_s(), hi = p.any_headway_max_s();
  std::vector<std::vector<int>> starts;
  std::string method_starts;
  // A start built from the problem's structure is annealed from a lower temperature (that of
  // the anytime rounds' re-annealing): from the full one its structure would be lost.
  std::vector<double> start_temperature;
  // A model whose starts are not priced (network: a load flow costs about a thousand times a
  // balance) builds its structured starts on its proxy (network: power-flow), on whose
  // annealing grid they are priced.
  std::unique_ptr<FleetEnergyModel> proxy, proxy_coarse;
  const bool structured_starts = options.regime_start || (options.relaxed_start && !p.windowed());
  if (structured_starts && !plan.price_starts && (proxy = model.start_proxy()))
    proxy_coarse = proxy->on_grid(options.anneal_step_s);
  const FleetEnergyModel& start_model = proxy ? *proxy : model;
  const FleetEnergyModel& start_coarse = proxy ? *proxy_coarse : *coarse;
  // The caller's timetables first (ties go to them), kept near their structure.
  for (const std::vector<int>& given : options.given_starts_s) {
    starts.push_back(given);
    start_temperature.push_back(options.reanneal_temperature);
  }
  if (!options.given_starts_s.empty())
    method_starts =
        options.given_starts_s.size() == 1 ? "the given timetable, " : "the given timetables, ";
  std::vector<int> relaxed_departures;
  if (options.relaxed_start && !p.windowed()) {
    // Every join of the maximisers near the span, priced on the annealing's grid side by side:
    // the best is the start (ties: the first).
    const std::vector<std::vector<int>> joins =
        relaxed_start_candidates(start_model.relaxation_maximisers_s(share_past(0.6)), p);
    std::vector<double> used(joins.size(), -1.0);
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads)
    for (long i = 0; i < static_cast<long>(joins.size()); ++i) {
      const std::vector<int> d = departures_from_headways(joins[i]);
      if (departures_problem(p, d).empty()) used[i] = start_coarse.evaluate(d).total.used_regen_J;
    }
    const auto best_join = std::max_element(used.begin(), used.end());
    if (best_join != used.end() && *best_join >= 0.0)
      relaxed_departures = departures_from_headways(joins[best_join - used.begin()]);
  }
  // Where more trains share the line than the relaxation values exactly a steady regime decides
  // the usage, with peak windows or without: the regime start (built beside the relaxed one,
  // which it beat on 120 trains and matched on 100 and 110). With a time limit it may take half
  // of what the bound and the relaxation left, a quarter beside the relaxed start (on 2.1 it
  // gives nothing, and a short limit's search needs the time); one that is not built by then
  // is dropped (the other starts remain), so that a short limit is kept.
  if (options.regime_start && (plan.price_starts || proxy)) {
    const double share = relaxed_departures.empty() ? 0.5 : 0.25;
    RegimeStart r = build_regime_start(
        start_coarse, p, threads, &start_model,
        ticking("periodic regimes", bound_used(), share_past(share, seconds_since(t0))));
    if (!r.departures_s.empty() && departures_problem(p, r.departures_s).empty()) {
      starts.push_back(std::move(r.departures_s));
      start_temperature.push_back(options.reanneal_temperature);
      char buf[256];
      std::snprintf(buf, sizeof buf,
                    "periodic regimes on a %d s grid (their runs reordered by %ld evaluations "
                    "of the %s model: used %.1f -> %.1f kJ), ",
                    r.grid_s, r.arrangement_evaluations, std::string(start_model.name()).c_str(),
                    r.dp_used_J * 1e-3, r.arranged_used_J * 1e-3);
      method_starts += buf;
    }
  }
  report("periodic regimes", 0.0, bound_used());
  const bool relaxed = !relaxed_departures.empty();  // a start from the relaxation was added
  if (relaxed) {
    starts.push_back(std::move(relaxed_departures));
    start_temperature.push_back(options.reanneal_temperature);
    method_starts += proxy ? "the " + std::string(start_model.name()) + " model's relaxation, "
                           : std::string("the bound's relaxation, ");
  }
  const std::vector<double> pair =
      (plan.two_train_values_on_search_grid ? *coarse : model).two_train_values_J(lo, hi, threads);
  report("two-train approximation", 0.0, bound_used());
  if (p.windowed())
    starts.push_back(departures_from_headways(maximise_windowed(p, both_classes(pair)).headways_s));
  else
    starts.push_back(departures_from_headways(maximise_separable(domain_of(p), pair).headways_s));
  // The uniform timetable: a start of no structure, left out when the relaxation gave one.
  if (!relaxed) starts.push_back(departures_from_headways(uniform_headways(p)));
  start_temperature.resize(starts.size(), 1.0);
  double evaluate_s = 0.0, traction_J = NAN;  // traction: the same for every timetable
  std::size_t best_start = 0;
  MicroJoules best_start_substation = 0;
  if (plan.price_starts) {
    for (std::size_t i = 0; i < starts.size(); ++i) {
      const auto e0 = Clock::now();
      const FleetEvaluation e = model.evaluate(starts[i]);
      const auto sub = static_cast<MicroJoules>(std::llround(e.total.substation_J() * 1e6));
      if (i == 0 || sub < best_start_substation) best_start = i, best_start_substation = sub;
      // The caller's timetables are the first starts (ties go to them).
      if (i < options.given_starts_s.size() && best_start == i)
        s.given_start_used_J = e.used_regen_J();
      s.start_used_J = std::max(s.start_used_J, e.total.used_regen_J);
      traction_J = e.total.traction_J;
      evaluate_s = std::max(evaluate_s, seconds_since(e0));
    }
  }
  report("starts", s.start_used_J, bound_used());
  // The search ends early enough for the result's evaluation to keep the limit too.
  const double search_limit =
      options.time_limit_s > 0.0 ? std::max(1e-9, options.time_limit_s - 2.0 * evaluate_s) : 0.0;

  // The polish grids of the plan's stages.
  std::vector<std::unique_ptr<FleetEnergyModel>> grids;
  for (const SearchPlan::Polish& stage : plan.polish) {
    const double step = polish_step(stage, options.anneal_step_s);
    grids.push_back(stage.step_s == 0.0 ? nullptr : model.on_grid(step));
  }
  // Anneals the runs (run r from start_of[r], its own counter-based draws), polishes their
  // results (or only the best) through the plan's stages and returns the best polished
  // timetable (ties: the lowest run), all on the model's grid; *stopped when a limit cut it.
  struct Round {
    std::vector<int> best;
    MicroJoules substation = 0;
    bool stopped = false;
    int refinements = 0;  // exact refinements that gained
  };
  const auto search_round = [&](const std::vector<std::vector<int>>& start_of,
                                const std::vector<std::uint64_t>& run_id,
                                const std::vector<double>& temperature, long moves,
                                double anneal_limit) {
    Round out;
    const int runs = static_cast<int>(start_of.size());
    std::vector<RunResult> results(runs);
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads)
    for (int r = 0; r < runs; ++r) {
      const std::unique_ptr<FleetBalance> balance = coarse->make_balance(1);
      results[r] = anneal(*balance, p, plan, start_of[r], options.seed, run_id[r], moves, t0,
                          anneal_limit, options.block_moves && p.windowed(), temperature[r]);
    }
    std::vector<std::vector<int>> candidates;
    std::size_t best_run = 0;
    for (std::size_t r = 0; r < results.size(); ++r) {
      s.moves += results[r].moves;
      out.stopped |= results[r].stopped;
      if (results[r].substation < results[best_run].substation) best_run = r;
    }
    if (plan.polish_every_run) {
      for (const auto& r : results) candidates.push_back(r.departures);
    } else {
      candidates.push_back(results[best_run].departures);
    }
    // Candidates side by side, each stage's balance on one thread; one candidate: its balance
    // on every thread. The best wins (ties: the first), whichever thread ran what.
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
            polish(*balance, p, candidates[c], window, stage.sweeps, t0, search_limit, &stop);
        polished[c] = balance->substation();
      }
      stopped[c] = stop;
    }
    std::size_t best_c = 0;
    for (int c = 0; c < n_candidates; ++c) {
      s.moves += polish_moves[c];
      out.stopped |= stopped[c] != 0;
      if (polished[c] < polished[best_c]) best_c = c;
    }
    out.best = candidates[best_c];
    out.substation = polished[best_c];
    // The model's exact search near the best moves many headways at once where the polish's
    // one-train moves had stopped; the polish then goes on from its result, while either gains.
    const int window = options.polish_window_s;
    for (int cycle = 0; options.exact_refine && !p.windowed() && cycle < 4; ++cycle) {
      if (past(t0, search_limit)) {
        out.stopped = true;
        break;
      }
      const double left = search_limit > 0.0 ? search_limit - seconds_since(t0) : 0.0;
      const std::vector<int> h =
          model.refined_headways_s(headways_from_departures(out.best), threads, left);
      if (h.empty()) break;
      std::vector<int> t = departures_from_headways(h);
      const std::unique_ptr<FleetBalance> balance = model.make_balance(threads);
      bool stop = false;
      s.moves += polish(*balance, p, t, window, 50, t0, search_limit, &stop);
      out.stopped |= stop;
      if (balance->substation() >= out.substation) break;
      out.best = std::move(t);
      out.substation = balance->substation();
      ++out.refinements;
      if (stop) break;
    }
    return out;
  };

  // Round 0: every start, restarts times, the model's share of the time limit for annealing.
  const int per_start =
      plan.run_without_restarts ? std::max(1, options.restarts) : options.restarts;
  const long moves = options.restarts == 0 ? 0 : options.moves_per_run;
  int runs = static_cast<int>(starts.size()) * per_start;
  std::vector<std::vector<int>> start_of;
  std::vector<std::uint64_t> run_id;
  std::vector<double> temperature;
  for (int r = 0; r < std::max<int>(runs, starts.size()); ++r) {  // runs 0: the starts polished
    start_of.push_back(starts[r % starts.size()]);
    temperature.push_back(start_temperature[r % starts.size()]);
    run_id.push_back(r);
  }
  Round best = search_round(start_of, run_id, temperature, runs == 0 ? 0 : moves,
                            plan.anneal_share_of_time_limit * search_limit);
  s.time_limit_reached = best.stopped;
  s.refinements = best.refinements;
  // A start priced on the model's grid better than every polished run stays the result.
  if (plan.price_starts && best_start_substation < best.substation)
    best.best = starts[best_start], best.substation = best_start_substation;
  // Progress in used energy where the starts were priced (else 0, as before any result).
  const auto used_of = [&](MicroJoules substation) {
    return std::isfinite(traction_J) ? traction_J - to_joules(substation) : 0.0;
  };
  report("round 0", used_of(best.substation), bound_used());

  // The model's exact search on part of the domain, with a time limit only (it may take
  // minutes; it gives up at once when it would not fit): its optimum replaces the result when
  // better.
  if (options.exact_part && options.time_limit_s > 0.0 && !p.windowed() && !best.stopped &&
      !past(t0, search_limit)) {
    const energy::ExactPartOptimum x = model.exact_part_optimum(
        headways_from_departures(best.best), threads, search_limit - seconds_since(t0));
    if (x.proven) {
      s.exact_part = x.part;
      s.exact_part_used_J = x.used_regen_J;
      if (!x.headways_s.empty()) {
        std::vector<int> d = departures_from_headways(x.headways_s);
        const std::unique_ptr<FleetBalance> balance = model.make_balance(threads);
        balance->place_all(d);
        if (balance->substation() < best.substation)
          best.best = std::move(d), best.substation = balance->substation();
      }
    }
    report("exact optimum of part of the domain", used_of(best.substation), bound_used());
  }

  // Anytime rounds: while time remains (with a limit) or for options.rounds rounds (without),
  // two runs a round: one re-anneals the best so far from a lower temperature, one anneals a
  // start afresh with new draws. A round a limit cuts short is dropped, so a run with more time
  // continues the run with less exactly (the same rounds in the same order, then more) and its
  // result is never worse.
  for (int round = 1; !best.stopped && runs > 0; ++round) {
    if (options.time_limit_s > 0.0 ? past(t0, search_limit) : round > options.rounds) break;
    const std::size_t fresh = round % starts.size();
    const std::vector<std::vector<int>> from = {best.best, starts[fresh]};
    const std::vector<std::uint64_t> ids = {1000003ULL * round, 1000003ULL * round + 1};
    const Round r =
        search_round(from, ids, {options.reanneal_temperature, start_temperature[fresh]},
                     std::max<long>(1, moves / 2), search_limit);
    if (r.stopped) {
      s.time_limit_reached = true;
      break;
    }
    ++s.rounds;
    s.refinements += r.refinements;
    if (r.substation < best.substation) best.best = r.best, best.substation = r.substation;
    report("round " + std::to_string(round), used_of(best.substation), bound_used());
  }

  // The caller's timetables bound the result. Where the plan prices its starts they were priced
  // with them, and a start better than every polished run stays the result; where it does not
  // (the network), they are priced here, on the model itself.
  out.evaluation = model.evaluate(best.best);
  double given_substation_J = INFINITY;
  for (std::size_t i = 0; !plan.price_starts && i < options.given_starts_s.size(); ++i) {
    FleetEvaluation e = model.evaluate(options.given_starts_s[i]);
    if (e.total.substation_J() < given_substation_J)
      given_substation_J = e.total.substation_J(), s.given_start_used_J = e.used_regen_J();
    if (e.total.substation_J() < out.evaluation.total.substation_J()) {
      best.best = e.departures_s;
      out.evaluation = std::move(e);
    }
  }
  out.headways_s = headways_from_departures(best.best);
  if (!bound_taken) bound_taken = bound_beside.get();
  const energy::FleetLowerBound& bound = *bound_taken;
  s.method =
      method_starts + "annealing (" + std::to_string(runs) + " runs, " + std::to_string(s.rounds) +
      " further rounds) and polish" + plan.method_note +
      (s.refinements > 0
           ? ", exact refinement on the core (" + std::to_string(s.refinements) + " gained)"
           : "") +
      (s.exact_part.empty() ? ""
                            : ", no timetable with " + s.exact_part + " is better (exact DP)") +
      (bound.name.empty() ? "" : ", " + bound.name);
  s.used_regen_J = out.evaluation.used_regen_J();
  s.substation_J = out.evaluation.total.substation_J();
  s.bound_used_regen_J = bound.used_regen_J;
  s.bound_substation_J = bound.substation_J;
  s.curtailed_traction_J =
      out.evaluation.network ? out.evaluation.network->curtailed_traction_J : 0.0;
  s.gap_fraction = bound.exists() ? model.gap_fraction(out.evaluation, bound) : NAN;
  s.pair_sum_J = model.pair_sum_J(best.best);
  settle_termination(s, options.gap_fraction,
                     out.evaluation.network && out.evaluation.network->unsolved_instants > 0);
  s.wall_s = seconds_since(t0);
  report("done", s.used_regen_J, s.bound_used_regen_J);
  return out;
}

}  // namespace ecorail::fleet
