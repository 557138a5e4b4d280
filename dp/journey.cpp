#include "dp/journey.hpp"

#include "dp/lambda_bracket.hpp"
#include "dp/section_library.hpp"
#include "dp/section_solve.hpp"
#include "dp/text_format.hpp"
#include "dp/threads.hpp"
#include "physics/energy_balance.hpp"
#include "physics/units.hpp"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <optional>

namespace ecorail::dp {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// Every section's run for one lambda. Sections are independent, so they run side by side
// (each one's sweep then runs on the thread it is given); results do not depend on which thread
// ran which section. A section whose source is another (a twin: equal track, same start) takes
// that one's run, which is bit for bit what its own engine would give.
// The first section may start mid-run (a restart).
// step_m: the re-simulation step of the runs (0: each engine's fine step).
std::vector<LambdaRun> run_all(const std::vector<const SectionEngine*>& engines,
                               const std::vector<std::size_t>& source, double lambda,
                               const StartState& start, double step_m) {
  std::vector<LambdaRun> runs(engines.size());
  const int n = static_cast<int>(engines.size());
#pragma omp parallel for schedule(dynamic, 1)
  for (int i = 0; i < n; ++i) {
    if (source[i] != static_cast<std::size_t>(i)) continue;
    const SectionEngine& e = *engines[i];
    runs[i] = e.run(lambda, i == 0 ? start : StartState{}, e.search_step_m(step_m));
  }
  for (int i = 0; i < n; ++i) {
    if (source[i] != static_cast<std::size_t>(i)) runs[i] = runs[source[i]];
  }
  return runs;
}

double total_time(const std::vector<LambdaRun>& runs) {
  double t = 0.0;
  for (const auto& r : runs) t += r.sim.running_time_s;
  return t;
}

// The same runs at each engine's fine step (from their kept value functions: no sweep). A twin
// whose run is its source's (same price) takes that one's fine run.
void refine_all(const std::vector<const SectionEngine*>& engines,
                const std::vector<std::size_t>& source, std::vector<LambdaRun>& runs) {
  const int n = static_cast<int>(runs.size());
  std::vector<char> own(runs.size());
  for (int i = 0; i < n; ++i) {
    own[i] = source[i] == static_cast<std::size_t>(i) || runs[i].lambda != runs[source[i]].lambda;
  }
#pragma omp parallel for schedule(dynamic, 1)
  for (int i = 0; i < n; ++i) {
    if (own[i]) runs[i] = engines[i]->fine_run(runs[i]);
  }
  for (int i = 0; i < n; ++i) {
    if (!own[i]) runs[i] = runs[source[i]];
  }
}

// Optimal split: regula falsi on log(lambda) for the total time, then a trim of one section.
// Where the frontiers put the price: log(lambda) and the slope of the total running time in it.
struct PricePrediction {
  double x = 0.0;
  double dT_dx = 0.0;  // negative; 0: no prediction
};

// The price is bracketed and narrowed on runs re-simulated at opt.search_step_m (coarse, as a
// section's search); the best price's runs are then made fine before the trim, which alone are
// returned. Returns whether their total running time meets the target to the tolerance.
bool optimal_split(const std::vector<const SectionEngine*>& engines,
                   const std::vector<std::size_t>& source, double target,
                   const TimeSearchOptions& opt, const StartState& start,
                   const PricePrediction& predicted, JourneySolution& out,
                   std::vector<LambdaRun>& best) {
  double best_err = INFINITY, best_x = std::log(opt.lambda_guess);
  double step_m = opt.search_step_m;
  auto evaluate = [&](double x) {
    std::vector<LambdaRun> runs = run_all(engines, source, std::exp(x), start, step_m);
    ++out.lambda_evaluations;
    report_progress(opt.progress, "lambda evaluation", out.lambda_evaluations, 0);
    const double f = total_time(runs) - target;
    if (std::abs(f) < best_err) {
      best_err = std::abs(f);
      best_x = x;
      best = std::move(runs);
      out.lambda_J_per_s = std::exp(x);
    }
    return f;
  };
  double coarse = opt.trim ? opt.lambda_tolerance_s : opt.tolerance_s;
  if (predicted.dT_dx < 0.0) {
    // Newton from the frontiers' price and slope, then secant steps on the measured times. The
    // total time of many sections is ragged in lambda by a few tenths of a second (each
    // section's grid), below which lambda steps chase noise; so from a prediction the search
    // hands over to the trim at kWarmTolerance_s: the trim moves one switch point along its
    // frontier, a first-order neutral move whose cost is second order in the gap.
    constexpr double kWarmTolerance_s = 0.5;
    if (opt.trim) coarse = std::max(coarse, kWarmTolerance_s);
    double x0 = predicted.x, f0 = evaluate(x0), slope = predicted.dT_dx;
    for (int k = 0; k < 3 && std::abs(f0) > coarse; ++k) {
      const double x1 = x0 - f0 / slope;
      const double f1 = evaluate(x1);
      if (f1 != f0 && (f1 - f0) / (x1 - x0) < 0.0) slope = (f1 - f0) / (x1 - x0);
      x0 = x1, f0 = f1;
    }
  }
  std::optional<LambdaBracket> bracket;
  auto narrow = [&](double tolerance) {
    if (!bracket) {
      const bool warm = predicted.dT_dx < 0.0;
      bracket.emplace(evaluate, warm ? best_x : std::log(opt.lambda_guess),
                      std::log(warm ? 1.03 : opt.bracket_factor), opt.max_iterations);
    }
    bracket->narrow([&] { return best_err <= tolerance; });
  };
  if (best_err > coarse) narrow(coarse);
  refine_all(engines, source, best);
  best_err = std::abs(total_time(best) - target);
  step_m = 0.0;  // from here on every run is fine
  // Close the rest on one section, the longest-running first (it has the most room to move);
  // if no section can, narrow lambda to the fine tolerance instead.
  if (best_err <= opt.tolerance_s) return true;
  const double residual = total_time(best) - target;
  std::vector<std::size_t> order(best.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return best[a].sim.running_time_s > best[b].sim.running_time_s;
  });
  for (std::size_t i : opt.trim ? order : std::vector<std::size_t>{}) {
    TimeSearchResult r;
    r.run = best[i];
    if (trim_to_time(*engines[i], best[i].sim.running_time_s - residual, opt.tolerance_s, r,
                     opt.search_step_m)) {
      best[i] = std::move(r.run);
      return true;
    }
  }
  // No one section can take the residual (equal sections jump in lambda together, so the
  // residual is a multiple of one section's jump): it is shared evenly by the k longest-running
  // sections, each trimmed by residual / k, for k = all, ..., 4, 2, the first that works. A trim
  // costs second order in its length at the optimum, so k sections sharing it cost 1/k of one
  // taking it all; for equal sections all k keep the split symmetric, as their common convex
  // frontier wants.
  std::vector<std::size_t> shares;  // all, ..., 8, 4, 2
  for (std::size_t k = 2; opt.trim && order.size() >= 2; k *= 2) {
    shares.insert(shares.begin(), std::min(k, order.size()));
    if (k >= order.size()) break;
  }
  for (const std::size_t k : shares) {
    std::vector<LambdaRun> trial = best;
    bool all = true;
    for (std::size_t j = 0; j < k && all; ++j) {
      const std::size_t i = order[j];
      TimeSearchResult r;
      r.run = best[i];
      all = trim_to_time(*engines[i], best[i].sim.running_time_s - residual / k,
                         opt.tolerance_s / k, r, opt.search_step_m);
      trial[i] = std::move(r.run);
    }
    if (all && std::abs(total_time(trial) - target) <= opt.tolerance_s) {
      best = std::move(trial);
      return true;
    }
  }
  narrow(opt.tolerance_s);
  return best_err <= opt.tolerance_s;
}

// The common price at which the sections' frontiers add up to the total running time, and the
// slope of that total in log(lambda), when the library holds every frontier already (asking
// never computes one) and the journey starts at rest; no prediction otherwise. Only a starting
// point for the search on re-simulated runs.
PricePrediction price_from_frontiers(const SectionLibrary& library, std::size_t first,
                                     std::size_t last, double total_time_s,
                                     const JourneyOptions& options) {
  if (!options.use_frontiers || !options.start.at_departure()) return {};
  for (std::size_t i = first; i < last; ++i) {
    if (!library.has_frontier(i)) return {};
  }
  auto total_at = [&](double x) {
    double t = 0.0;
    for (std::size_t i = first; i < last; ++i) {
      t += library.frontier(i).time_for_marginal(std::exp(x));
    }
    return t;
  };
  double lo = 0.0, hi = std::log(1e12);  // total time falls as the price rises
  if (total_at(lo) < total_time_s || total_at(hi) > total_time_s) return {};  // off the curves
  for (int k = 0; k < 100 && hi - lo > 1e-9; ++k) {
    const double mid = 0.5 * (lo + hi);
    (total_at(mid) > total_time_s ? lo : hi) = mid;
  }
  PricePrediction p;
  p.x = 0.5 * (lo + hi);
  constexpr double h = 0.02;
  p.dT_dx = (total_at(p.x + h) - total_at(p.x - h)) / (2.0 * h);
  if (!(p.dT_dx < 0.0)) return {};
  return p;
}

// The journey's summary from its solution, under the names and units of a section's; met says
// whether the search met the total time and every section its stop with a closed energy balance.
void summarise_journey(const std::vector<physics::Route>& routes, double min_total_s,
                       const JourneyOptions& options, bool met, JourneySolution& sol) {
  JourneySummary& s = sol.summary;
  s.from = routes.front().from_name();
  s.to = routes.back().to_name();
  s.sections = static_cast<int>(routes.size());
  s.split = options.split;
  for (const auto& r : routes) s.distance_m += r.length_m();
  s.distance_m -= options.start.position_m;
  s.target_time_s = sol.target_time_s;
  s.min_time_s = min_total_s;
  s.grid = options.engine.grid;
  s.threads = omp_get_max_threads();
  s.objective = options.engine.objective;
  s.lambda_J_per_s = sol.lambda_J_per_s;
  s.lambda_evaluations = sol.lambda_evaluations;
  s.build_wall_s = sol.build_wall_s;
  s.search_wall_s = sol.search_wall_s;
  s.total_wall_s = sol.total_wall_s;
  s.running_time_s = sol.running_time_s;
  s.traction_energy_kJ = units::J_to_kJ(sol.traction_work_J);
  s.braking_energy_kJ = units::J_to_kJ(sol.brake_work_J);
  s.regen_energy_kJ = units::J_to_kJ(sol.regen_J);
  s.net_energy_kJ = units::J_to_kJ(sol.net_J);
  bool arrives = true;
  for (const JourneySection& sec : sol.sections) {
    const physics::SimulationResult& sim = sec.run.sim;
    s.dwell_time_s += sec.dwell_after_s;
    if (std::abs(sim.stop_error_m) > std::abs(s.stop_error_m)) s.stop_error_m = sim.stop_error_m;
    s.max_overspeed_kmh =
        std::max(s.max_overspeed_kmh, units::ms_to_kmh(std::max(0.0, sim.max_overspeed_ms)));
    arrives = arrives && run_arrives(sim);
  }
  s.termination = termination_of(arrives, met);
  s.warnings = sol.warnings;
}

}  // namespace

std::string JourneySummary::BriefReport() const {
  // The time price in the one format of every report (lambda_text).
  const std::string price =
      std::isfinite(lambda_J_per_s) ? ", lambda " + lambda_text(lambda_J_per_s) : std::string();
  return format_text(
      "ecorail solve %s -> %s (%d sections, %s split) in %.3f s running time: traction %.1f "
      "kJ, regenerated %.1f kJ%s, %.3f s wall, %s\n",
      from.c_str(), to.c_str(), sections, std::string(split_name(split)).c_str(), running_time_s,
      traction_energy_kJ, regen_energy_kJ, price.c_str(), total_wall_s,
      std::string(status_word(termination, warnings.size())).c_str());
}

std::string JourneySummary::FullReport() const {
  std::string r = "\necorail journey solver report\n\n";
  r +=
      format_text("  %-28s %s -> %s, %d sections\n", "Journey", from.c_str(), to.c_str(), sections);
  r += format_text("  %-28s %.1f m\n", "Distance", distance_m);
  r += format_text("  %-28s %.3f s (minimum %.3f s), dwells %.3f s\n", "Target running time",
                   target_time_s, min_time_s, dwell_time_s);
  r += format_text("  %-28s %s\n", "Split", std::string(split_name(split)).c_str());
  r += format_text("  %-28s %s\n", "Objective", std::string(objective_name(objective)).c_str());
  r += format_text("  %-28s ds %.3g m, dv %.3g km/h, substep %.3g m\n", "Grid", grid.ds_m,
                   grid.dv_kmh, grid.substep_m);
  r += format_text("  %-28s %d\n", "Threads", threads);
  if (streamed_tables) {
    r += format_text("  %-28s built per sweep: all together %.2f GiB would exceed the budget\n",
                     "Transition tables", tables_estimate_bytes / 1073741824.0);
  }
  if (std::isfinite(lambda_J_per_s)) {
    r += format_text("  %-28s %s\n", "Lambda (time price)", lambda_text(lambda_J_per_s).c_str());
  }
  r += format_text("  %-28s %d lambda evaluations\n", "Search", lambda_evaluations);
  r += format_text("  %-28s %.4f s build, %.4f s search, %.4f s total\n", "Wall time", build_wall_s,
                   search_wall_s, total_wall_s);
  r += result_block_text({running_time_s, traction_energy_kJ, braking_energy_kJ, regen_energy_kJ,
                          net_energy_kJ, "Stop error (largest)", stop_error_m, max_overspeed_kmh,
                          termination, &warnings});
  return r;
}

physics::Trip journey_trip(const JourneySolution& solution,
                           const std::vector<physics::Route>& routes, double departure_s,
                           double regen_efficiency) {
  if (routes.size() != solution.sections.size()) {
    throw std::invalid_argument("a journey trip needs one route per section of the solution");
  }
  std::vector<physics::TripSection> sections;
  for (std::size_t i = 0; i < routes.size(); ++i) {
    const JourneySection& sec = solution.sections[i];
    sections.push_back({&routes[i], &sec.run.sim, i + 1 < routes.size() ? sec.dwell_after_s : 0.0});
  }
  return physics::Trip(sections, departure_s, regen_efficiency);
}

bool JourneyOptions::IsValid(std::string* error) const {
  auto fail = [&](const char* why) {
    if (error) *error = why;
    return false;
  };
  if (!engine.IsValid(error) || !search.IsValid(error) || !min_regime.IsValid(error)) return false;
  if (split != Split::Optimal && split != Split::Proportional) {
    return fail("split must be optimal or proportional");
  }
  if (!(marginal_step_s > 0.0 && marginal_step_s <= 10.0)) {
    return fail("marginal_step_s must be in (0, 10] s");
  }
  if (!(start.position_m >= 0.0 && std::isfinite(start.position_m))) {
    return fail("start position_m must be a finite position >= 0 m");
  }
  if (!(start.speed_ms >= 0.0 && std::isfinite(start.speed_ms))) {
    return fail("start speed_ms must be a finite speed >= 0 m/s");
  }
  return true;
}

JourneySolution solve_journey(const physics::Train& train,
                              const std::vector<physics::Route>& routes,
                              const std::vector<double>& dwells_s, double total_time_s,
                              const JourneyOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw std::invalid_argument(why);
  SectionLibraryOptions lo;
  lo.engine = options.engine;
  lo.search = options.search;
  const SectionLibrary library(train, routes, lo);
  return solve_journey(library, 0, library.size(), dwells_s, total_time_s, options);
}

JourneySolution solve_journey(const SectionLibrary& library, std::size_t first, std::size_t last,
                              const std::vector<double>& dwells_s, double total_time_s,
                              const JourneyOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw std::invalid_argument(why);
  const ThreadScope threads(options.engine.threads);
  const auto t0 = Clock::now();
  if (!(first < last && last <= library.size())) {
    throw std::invalid_argument("a journey needs sections [first, last) of the library");
  }
  JourneySolution out;
  out.target_time_s = total_time_s;
  library.build_engines(first, last);  // only those not built yet
  std::vector<const SectionEngine*> engines;
  std::vector<physics::Route> routes;
  double min_total = 0.0, length = 0.0;
  std::vector<double> min_times, remaining_m;
  // Each section's source of runs (run_all): its first twin in the journey, unless that is a
  // restart's first section, which starts elsewhere.
  std::vector<std::size_t> source;
  std::map<std::size_t, std::size_t> first_of_twin;
  const bool restarts = !options.start.at_departure();
  for (std::size_t i = first; i < last; ++i) {
    const bool own = restarts && i == first;
    const std::size_t k = i - first;
    source.push_back(own ? k : first_of_twin.emplace(library.twin(i), k).first->second);
    engines.push_back(&library.engine(i));
    routes.push_back(library.route(i));
    const bool restart = i == first && !options.start.at_departure();
    min_times.push_back(restart ? library.engine(i).min_time_run(options.start).running_time_s
                                : library.min_time_s(i));
    min_total += min_times.back();
    remaining_m.push_back(routes.back().length_m() - (restart ? options.start.position_m : 0.0));
    length += remaining_m.back();
  }
  out.build_wall_s = seconds_since(t0);
  if (total_time_s < min_total - options.search.tolerance_s) {
    throw InfeasibleTimeError(total_time_s, min_total,
                              routes.front().from_name() + " -> " + routes.back().to_name() +
                                  " (sum of flat-out sections, dwells excluded)");
  }

  const auto t1 = Clock::now();
  std::vector<LambdaRun> runs;
  bool time_met = false;  // the search met the total running time
  if (options.split == Split::Optimal) {
    const PricePrediction predicted =
        price_from_frontiers(library, first, last, total_time_s, options);
    time_met = optimal_split(engines, source, total_time_s, options.search, options.start,
                             predicted, out, runs);
    if (!time_met && engines.front()->searches_coarse(options.search.search_step_m)) {
      // As a section's search (solve_for_time): where the coarse runs' own decisions make their
      // times differ from the fine runs' (long, slow runs: A6 -> A8 in 1100 s with 30 s
      // dwells), the price is searched again on fine runs only.
      TimeSearchOptions fine = options.search;
      fine.search_step_m = 0.0;
      runs.clear();
      time_met =
          optimal_split(engines, source, total_time_s, fine, options.start, predicted, out, runs);
    }
  } else {
    out.lambda_J_per_s = NAN;
    time_met = true;
    for (std::size_t i = 0; i < engines.size(); ++i) {
      const double share = total_time_s * remaining_m[i] / length;
      if (share < min_times[i]) {
        throw TimeRequestError(format_text(
            "the proportional share %.2f s of section %s -> %s is below its minimum running "
            "time %.2f s",
            share, routes[i].from_name().c_str(), routes[i].to_name().c_str(), min_times[i]));
      }
      TimeSearchResult r =
          solve_for_time(*engines[i], share, options.search, i == 0 ? options.start : StartState{});
      out.lambda_evaluations += r.iterations;
      time_met = time_met && r.converged;
      runs.push_back(std::move(r.run));
    }
  }
  out.search_wall_s = seconds_since(t1);

  // A minimum regime: each section merged and trimmed back to its own running time.
  for (std::size_t i = 0; i < runs.size() && options.min_regime.active(); ++i) {
    MinRegimeResult m =
        enforce_min_regime(*engines[i], runs[i], runs[i].sim.running_time_s, options.min_regime);
    out.merged_regimes += m.merged_entries;
    out.unmerged_cost_J += m.cost_before_J;
    out.merged_cost_J += m.cost_after_J;
    if (m.short_entries_left > 0) {
      out.warnings.push_back(format_text(
          "section %s -> %s: %d control phases remain below the "
          "minimum regime",
          routes[i].from_name().c_str(), routes[i].to_name().c_str(), m.short_entries_left));
    }
    runs[i] = std::move(m.run);
  }
  for (std::size_t i = 0; i < runs.size(); ++i) {
    JourneySection sec;
    sec.run = std::move(runs[i]);
    sec.regimes = regime_spans(sec.run.sim.trace, std::max(0.5, options.min_regime.min_length_m));
    sec.dwell_after_s = i < dwells_s.size() ? dwells_s[i] : 0.0;
    sec.min_time_s = min_times[i];
    sec.marginal_J_per_s = NAN;
    const auto& sim = sec.run.sim;
    out.running_time_s += sim.running_time_s;
    out.traction_work_J += sim.energy.traction_work_J;
    out.brake_work_J += sim.energy.brake_work_J;
    out.regen_J += sim.energy.regen_J;
    out.net_J += sim.energy.net_J();
    out.sections.push_back(std::move(sec));
  }
  if (options.measure_marginals) {
    // -(dE/dT) by central difference of two fresh solves of the section alone. The 2n solves
    // run side by side, not a section's two in turn: a journey's longest section would else
    // keep one thread busy while the others wait (a 34.8 km TTOBench section: docs/performance.md).
    const double h = options.marginal_step_s;
    const int n = static_cast<int>(out.sections.size());
    std::vector<double> cost_J(2 * static_cast<std::size_t>(n), NAN),
        time_s(2 * static_cast<std::size_t>(n), NAN);  // [2i]: slower by h, [2i + 1]: faster
#pragma omp parallel for schedule(dynamic, 1)
    for (int k = 0; k < 2 * n; ++k) {
      const int i = k / 2;
      const double t = out.sections[i].run.sim.running_time_s;
      if (t - h < min_times[i]) continue;
      const StartState start = i == 0 ? options.start : StartState{};
      const auto r = solve_for_time(*engines[i], k % 2 == 0 ? t + h : t - h, options.search, start);
      cost_J[k] = engines[i]->energy_cost_J(r.run.sim);
      time_s[k] = r.run.sim.running_time_s;
    }
    for (int i = 0; i < n; ++i) {
      if (std::isnan(cost_J[2 * i])) continue;
      out.sections[i].marginal_J_per_s =
          (cost_J[2 * i + 1] - cost_J[2 * i]) / (time_s[2 * i] - time_s[2 * i + 1]);
    }
  }
  // Every section must come to rest at its stop: a journey with one that does not is never a
  // converged result.
  bool met = time_met;
  for (std::size_t i = 0; i < out.sections.size(); ++i) {
    const physics::SimulationResult& sim = out.sections[i].run.sim;
    if (!run_meets_targets(sim, 0.0)) {
      met = false;
      char msg[200];
      std::snprintf(msg, sizeof msg, "section %s -> %s misses its stop by %.2f m",
                    routes[i].from_name().c_str(), routes[i].to_name().c_str(), sim.stop_error_m);
      out.warnings.push_back(msg);
    }
    // The last check before a result: its energy balances (physics/energy_balance.hpp).
    const physics::EnergyBalance balance = physics::energy_balance(engines[i]->motion(), sim);
    if (!balance.closes()) {
      met = false;
      out.warnings.push_back(
          format_text("section %s -> %s: energy does not balance by %.1f kJ (dissipation %.1f kJ)",
                      routes[i].from_name().c_str(), routes[i].to_name().c_str(),
                      balance.residual_J / 1e3, balance.dissipation_J / 1e3));
    }
  }
  if (!time_met) {
    out.warnings.push_back("total running time not met to " +
                           std::to_string(options.search.tolerance_s) + " s");
  }
  out.total_wall_s = seconds_since(t0);
  summarise_journey(routes, min_total, options, met, out);
  out.summary.streamed_tables = library.streams_tables();
  out.summary.tables_estimate_bytes = library.tables_estimate_bytes();
  return out;
}

JourneySolution solve_journey_free_dwells(const SectionLibrary& library, std::size_t first,
                                          std::size_t last, const std::vector<DwellRange>& dwells,
                                          double trip_time_s, const JourneyOptions& options) {
  if (!(first < last && last <= library.size()) || dwells.size() + 1 != last - first) {
    throw std::invalid_argument("free dwells need one dwell range per intermediate stop");
  }
  std::vector<double> chosen;
  double dwell_total = 0.0;
  for (const DwellRange& d : dwells) {
    if (!(d.min_s >= 0.0 && d.max_s >= d.min_s && std::isfinite(d.max_s))) {
      throw std::invalid_argument("a dwell range needs 0 <= min <= max, finite");
    }
    chosen.push_back(d.min_s);  // see the header: the optimum takes every minimum
    dwell_total += d.min_s;
  }
  double min_running = 0.0;
  for (std::size_t i = first; i < last; ++i) {
    const bool restart = i == first && !options.start.at_departure();
    min_running += restart ? library.engine(i).min_time_run(options.start).running_time_s
                           : library.min_time_s(i);
  }
  if (trip_time_s < min_running + dwell_total - options.search.tolerance_s) {
    throw InfeasibleTimeError(trip_time_s, min_running + dwell_total,
                              library.route(first).from_name() + " -> " +
                                  library.route(last - 1).to_name() +
                                  " (sum of flat-out sections plus minimum dwells)");
  }
  return solve_journey(library, first, last, chosen, trip_time_s - dwell_total, options);
}

}  // namespace ecorail::dp
