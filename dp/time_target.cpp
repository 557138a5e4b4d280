#include "dp/time_target.hpp"

#include "dp/lambda_bracket.hpp"
#include "dp/text_format.hpp"
#include "physics/units.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace ecorail::dp {

namespace {
std::string long_message(double requested, double maximum) {
  // A request far beyond any running time (1e308 s) in short scientific form.
  return format_text(requested < 1e7 ? "running time %.2f s is above the longest running time of "
                                       "%.2f s this engine solves reliably for this section on "
                                       "this grid"
                                     : "running time %.6g s is above the longest running time of "
                                       "%.2f s this engine solves reliably for this section on "
                                       "this grid",
                     requested, maximum);
}

std::string infeasible_message(double requested, double minimum) {
  return format_text(
      "running time %.2f s is below the minimum running time of %.2f s for this section "
      "(flat-out run)",
      requested, minimum);
}
}  // namespace

InfeasibleTimeError::InfeasibleTimeError(double requested_s, double minimum_s, std::string subject)
    : TimeRequestError(infeasible_message(requested_s, minimum_s)),
      minimum_s_(minimum_s),
      requested_s_(requested_s),
      subject_(std::move(subject)) {}

LongTimeError::LongTimeError(double requested_s, double maximum_s)
    : TimeRequestError(long_message(requested_s, maximum_s)), maximum_s_(maximum_s) {}

bool TimeSearchOptions::IsValid(std::string* error) const {
  auto fail = [&](const char* why) {
    if (error) *error = why;
    return false;
  };
  if (!(tolerance_s > 0.0 && tolerance_s <= kTimeTolerance_s)) {
    return fail("search tolerance_s must be in (0, 0.1] s");
  }
  if (!(lambda_tolerance_s >= tolerance_s && std::isfinite(lambda_tolerance_s))) {
    return fail("search lambda_tolerance_s must be a finite number of seconds >= tolerance_s");
  }
  if (max_iterations < 1) return fail("search max_iterations must be at least 1");
  if (!(lambda_guess > 0.0 && std::isfinite(lambda_guess))) {
    return fail("search lambda_guess must be a positive price in J/s");
  }
  if (!(bracket_factor > 1.0 && std::isfinite(bracket_factor))) {
    return fail("search bracket_factor must be a finite factor > 1");
  }
  if (!(search_step_m >= 0.0 && search_step_m <= 10.0)) {
    return fail("search search_step_m must be in [0, 10] m");
  }
  if (!cruise_polish.IsValid(error)) return false;
  return true;
}

bool run_arrives(const physics::SimulationResult& sim) {
  return !sim.stopped_early && std::abs(sim.stop_error_m) <= kStopTolerance_m;
}

SlowLimit find_slow_limit(const SectionEngine& engine, const StartState& start) {
  SlowLimit out;
  // True when the run at exp(x) arrives and is slower than every run before it.
  auto slower = [&](double x) {
    LambdaRun run = engine.run(std::exp(x), start);
    ++out.evaluations;
    if (!run_arrives(run.sim) || run.sim.running_time_s <= out.max_time_s) return false;
    out.max_time_s = run.sim.running_time_s;
    out.lambda_J_per_s = run.lambda;
    out.scan.emplace_back(run.lambda, run.sim.running_time_s);
    out.run = std::move(run);
    return true;
  };
  double x_good = NAN, x_bad = NAN;
  // Down to lambda = 1 J/s, a price far below any useful one.
  for (double x = std::log(kSlowScanStart_J_per_s); x >= 0.0; x -= std::log(2.0)) {
    if (!slower(x)) {
      x_bad = x;
      break;
    }
    x_good = x;
  }
  if (std::isnan(x_good) || std::isnan(x_bad)) return out;
  for (int k = 0; k < kSlowScanRefinements; ++k) {
    const double mid = 0.5 * (x_good + x_bad);
    (slower(mid) ? x_good : x_bad) = mid;
  }
  return out;
}

bool LatticeRuns::find(double lambda, LambdaRun* run) const {
  const std::lock_guard<std::mutex> lock(mutex_);
  const auto it = runs_.find(lambda);
  if (it == runs_.end()) return false;
  *run = it->second;
  return true;
}

void LatticeRuns::keep(const LambdaRun& run) {
  const std::lock_guard<std::mutex> lock(mutex_);
  runs_.emplace(run.lambda, run);
}

namespace {
TimeSearchResult search_for_time(const SectionEngine& engine, double target,
                                 const TimeSearchOptions& options, const StartState& start,
                                 LatticeRuns* memo) {
  const physics::SimulationResult flat_out = engine.min_time_run(start);
  if (flat_out.stopped_early) {
    throw std::invalid_argument("the train cannot reach the end of the section from this state");
  }
  const double t_min = flat_out.running_time_s;
  if (target < t_min - options.tolerance_s) {
    const std::string section = engine.route().from_name() + " -> " + engine.route().to_name();
    throw InfeasibleTimeError(
        target, t_min,
        start.at_departure()
            ? section + " (flat-out run)"
            : format_text("the rest of %s from %.1f m at %.1f km/h "
                          "(flat-out run)",
                          section.c_str(), start.position_m, units::ms_to_kmh(start.speed_ms)));
  }

  TimeSearchResult out;
  bool have_best = false;
  // A run that does not arrive is no candidate: it scores infinitely far from the target and,
  // for the bracket, counts as too slow (it comes from a price below the slow limit).
  auto error_of = [&](const LambdaRun& run) {
    return run_arrives(run.sim) ? std::abs(run.sim.running_time_s - target) : INFINITY;
  };
  auto error_of_best = [&] { return have_best ? error_of(out.run) : INFINITY; };
  // The bracket is found and narrowed on runs re-simulated at the search step (coarse); the
  // best run is re-run at the fine step before it is trimmed or returned (refine).
  const double coarse_step = engine.search_step_m(options.search_step_m);
  double step_now = coarse_step;
  bool best_is_coarse = false;
  auto consider = [&](LambdaRun run, bool coarse) {
    if (!have_best || error_of(run) < error_of_best()) {
      out.run = std::move(run);
      have_best = true;
      best_is_coarse = coarse;
    }
  };
  auto refine = [&] {
    if (!have_best || !best_is_coarse) return;
    out.run = engine.fine_run(out.run);
    ++out.iterations;
    best_is_coarse = false;
  };
  // While the bracket walks the lattice, runs come from (and go to) the memo.
  bool walking = memo != nullptr;
  auto evaluate = [&](double x) {
    LambdaRun run;
    if (!(walking && memo->find(std::exp(x), &run))) {
      run = engine.run(std::exp(x), start, step_now);
      ++out.iterations;
      if (walking) memo->keep(run);
      report_progress(options.progress, "lambda evaluation", out.iterations, 0);
    }
    const double f = run_arrives(run.sim) ? run.sim.running_time_s - target : INFINITY;
    consider(std::move(run), engine.searches_coarse(step_now));
    return f;
  };
  auto trimmed = [&] {
    if (!options.trim) return false;
    TimeSearchResult attempt = out;
    if (!trim_to_time(engine, target, options.tolerance_s, attempt, options.search_step_m)) {
      out.trim_iterations = attempt.trim_iterations;
      return false;
    }
    out = std::move(attempt);
    return true;
  };

  LambdaBracket bracket(evaluate, std::log(options.lambda_guess), std::log(options.bracket_factor),
                        options.max_iterations);
  walking = false;
  // First to the coarse tolerance, where the trim takes over; if the trim cannot close the gap
  // (or only at a price far above lambda), on to kFallbackLambdaTolerance_s on coarse runs and
  // the trim again; then on to the fine tolerance on fine runs without it.
  std::vector<double> phases = {options.trim ? options.lambda_tolerance_s : options.tolerance_s};
  if (options.trim && options.lambda_tolerance_s > kFallbackLambdaTolerance_s) {
    phases.push_back(kFallbackLambdaTolerance_s);
  }
  phases.push_back(options.tolerance_s);
  auto close = [&](LambdaBracket& b) {
    step_now = coarse_step;
    for (std::size_t k = 0; k < phases.size(); ++k) {
      const bool last_phase = k + 1 == phases.size();
      if (last_phase) step_now = engine.options().resim_step_m;  // the fine tolerance on fine runs
      b.narrow([&] { return error_of_best() <= phases[k]; });
      if (best_is_coarse && options.trim && error_of_best() > options.tolerance_s &&
          std::isfinite(error_of_best())) {
        // Trimmed on coarse runs, checked by a fine one: no fine run of the untrimmed program.
        TimeSearchResult attempt = out;
        if (trim_via_coarse_runs(engine, target, options.tolerance_s, attempt, coarse_step, 0.0)) {
          out = std::move(attempt);
          best_is_coarse = false;
          return true;
        }
        out.trim_iterations = attempt.trim_iterations;
        if (!last_phase) continue;  // a closer price first
      }
      refine();
      if (error_of_best() <= options.tolerance_s || trimmed()) return true;
    }
    return false;
  };
  // A converged run's long cruise is polished (only ever replaced by a cheaper run in time).
  auto polish = [&] {
    report_progress(options.progress, "cruise polish", 0, 0);
    out.cruise_polish =
        polish_cruise(engine, target, options.tolerance_s, options.cruise_polish, out.run);
  };
  if (close(bracket)) {
    out.converged = true;
    out.held_excess_share = out.run.held_excess_share;
    polish();
    return out;
  }
  // Not met. Either the time is beyond the slow limit (refused, like one below the flat-out
  // run), or the bracket held prices below it: search again between the slow limit's price and
  // the nearest faster run of its scan, where running time grows as lambda falls.
  SlowLimit limit = find_slow_limit(engine, start);
  out.iterations += limit.evaluations;
  out.max_time_s = limit.max_time_s;
  if (limit.scan.empty()) return out;
  if (target > limit.max_time_s + options.tolerance_s) {
    throw LongTimeError(target, limit.max_time_s);
  }
  double x_lo = std::log(limit.lambda_J_per_s), f_lo = limit.max_time_s - target;
  double x_hi = std::log(1e9), f_hi = NAN;
  for (const auto& [lambda, time] : limit.scan) {
    if (time < target) x_hi = std::log(lambda), f_hi = time - target;
  }
  consider(std::move(limit.run), false);
  if (std::isnan(f_hi)) f_hi = evaluate(x_hi);
  LambdaBracket slow_side(evaluate, x_lo, f_lo, x_hi, f_hi, options.max_iterations);
  out.converged = close(slow_side);
  out.held_excess_share = out.run.held_excess_share;
  if (out.converged) polish();
  return out;
}
}  // namespace

namespace {
// The search on coarse runs, and on fine runs where those cannot meet the time.
TimeSearchResult search_coarse_then_fine(const SectionEngine& engine, double target,
                                         const TimeSearchOptions& options, const StartState& start,
                                         LatticeRuns* memo) {
  TimeSearchResult coarse = search_for_time(engine, target, options, start, memo);
  if (coarse.converged || !engine.searches_coarse(options.search_step_m)) return coarse;
  // A coarse run's program is decided on its own re-simulation (held cruises, coasting instead
  // of braking holds), so where those decisions flip its running time can differ from the fine
  // run's by seconds, and a time in such a place can be out of the coarse search's reach (A5 ->
  // A6 in 152 s: a 6 s jump of the coarse running time where the fine one is smooth). Then the
  // search runs again on fine runs only.
  TimeSearchOptions fine = options;
  fine.search_step_m = 0.0;
  TimeSearchResult out = search_for_time(engine, target, fine, start, nullptr);
  out.iterations += coarse.iterations;
  out.trim_iterations += coarse.trim_iterations;
  return out;
}
}  // namespace

TimeSearchResult solve_for_time(const SectionEngine& engine, double target,
                                const TimeSearchOptions& options, const StartState& start,
                                LatticeRuns* memo) {
  TimeSearchResult out = search_coarse_then_fine(engine, target, options, start, memo);
  if (!out.converged || !engine.options().cruise_as_hold ||
      !(out.held_excess_share > kGridCruisesCheckShare)) {
    return out;
  }
  // The converged run cost more held than as the grid has it, at its price: a run of phases that
  // looks like a saw tooth and is none (on CH_Fribourg_Bern with the VIRM6 at its minimum time
  // + 10 % the held run that met the time cost 4.3 % more than the grid's own). The time is
  // searched again on the grid's own cruises, and the cheaper run kept; the held run (and its
  // polish) is never replaced by a dearer one.
  report_progress(options.progress, "grid cruises", 0, 0);
  const SectionEngine grid_engine(engine, SectionEngine::GridCruises{});
  const TimeSearchResult grid =
      search_coarse_then_fine(grid_engine, target, options, start, nullptr);
  out.grid_cruises_searched = true;
  out.iterations += grid.iterations;
  out.trim_iterations += grid.trim_iterations;
  if (grid.converged && grid.run.cost_J < out.run.cost_J) {
    out.grid_cruises_kept = true;
    out.grid_cruises_saving_J = out.run.cost_J - grid.run.cost_J;
    out.run = grid.run;
    out.trim_shift_m = grid.trim_shift_m;
    // The held run's polish is not the run's (its re-simulations were spent all the same).
    const int polish_simulations = out.cruise_polish.simulations;
    out.cruise_polish = CruisePolishReport{};
    out.cruise_polish.simulations = polish_simulations;
  }
  return out;
}

namespace {
// The trim's root search in one switch position: at most this many re-simulations, down to a
// bracket this narrow.
constexpr int kTrimEvaluations = 40;
constexpr double kTrimExcessShare = 0.1;
constexpr double kTrimExcessFloor = 1e-5;
constexpr double kTrimGapScale_s = 0.5;
constexpr double kTrimMinWidth_m = 1e-9;
}  // namespace

namespace {
// The trim on runs re-simulated at step_m (result.run.sim must be a run at that step): every
// probe and trial is resumed at that step.
bool trim_at_step(const SectionEngine& engine, double target, double tolerance_s,
                  TimeSearchResult& result, double step_m, bool from_optimum) {
  LambdaRun& run = result.run;
  // A re-simulation that does not arrive counts as too slow and is never accepted.
  auto error = [&](const physics::SimulationResult& sim) {
    return run_arrives(sim) ? sim.running_time_s - target : INFINITY;
  };
  if (std::abs(error(run.sim)) <= tolerance_s) return true;
  const physics::ControlProgram program = run.program;
  const double length = engine.route().length_m();
  // Candidate switch points: the ends of full-traction phases, most time-sensitive first (a
  // switch held on the speed envelope barely moves the running time).
  struct Candidate {
    std::size_t index;
    double slope;  // d(time)/d(position), negative: later switch, faster run
  };
  std::vector<Candidate> candidates;
  // Every probe and trial moves one switch of `program`: it is the base run up to the switch's
  // smaller position, so it is resumed (bit for bit) from whichever earlier run, the base or
  // the trial before it, agrees with it further.
  physics::SimulationResult recent_sim;
  auto resimulate = [&](const physics::ControlProgram& trial) {
    const bool recent_closer = !recent_sim.checkpoints.empty() &&
                               physics::first_difference_m(trial, recent_sim.checkpoint_program) >
                                   physics::first_difference_m(trial, run.sim.checkpoint_program);
    physics::SimulationResult sim =
        engine.resimulate(trial, run.start, step_m, recent_closer ? recent_sim : run.sim);
    recent_sim = sim;
    return sim;
  };
  constexpr double kProbe_m = 0.5;
  for (std::size_t k = 1; k < program.size(); ++k) {
    if (program[k - 1].control != physics::Control::MaxTraction) continue;
    const double hi = k + 1 < program.size() ? program[k + 1].from_m : length;
    if (program[k].from_m + kProbe_m >= hi) continue;
    physics::ControlProgram probe = program;
    probe[k].from_m += kProbe_m;
    const double slope = (error(resimulate(probe)) - error(run.sim)) / kProbe_m;
    ++result.trim_iterations;
    if (slope < 0.0) candidates.push_back({k, slope});
  }
  std::sort(candidates.begin(), candidates.end(),
            [](const Candidate& a, const Candidate& b) { return a.slope < b.slope; });

  // A trim moves along the frontier only from an optimum and only to first order: a switch
  // whose move buys the time far dearer than the run's price (e.g. a traction phase stretched
  // past a limit and braked back) is no trim of this run. Accepted: at most the first-order
  // cost, cost + lambda * (time - target), plus a tenth of the price of the gap and a
  // hundred-thousandth of the cost (measured: A5 -> A6 in 157 s, trimmed by 0.37 s, went from
  // 64.9 MJ to 68.6 MJ by the most time-sensitive switch; its neighbours cost 66.0 and 64.4 MJ;
  // a tenth keeps every trim of the A6 -> A7 frontier, a twentieth sent points to the fine
  // search). Only for a run that is an optimum of its price (from_optimum).
  const double base_cost_J = run.cost_J;
  // The second-order part grows with the square of the gap: beyond kTrimGapScale_s the
  // allowance grows with it (a journey's section trimmed 80 s slower at 4.7 kJ/s saves 307 kJ
  // where the first order says 375 kJ: a good trim, 18 % short of the first order).
  const double gap_s = std::isfinite(error(run.sim)) ? std::abs(error(run.sim)) : 0.0;
  const double gap_price_J = run.lambda * gap_s * std::max(1.0, gap_s / kTrimGapScale_s);
  const double along_frontier_J =
      base_cost_J + run.lambda * (std::isfinite(error(run.sim)) ? error(run.sim) : 0.0);
  for (const Candidate& cand : candidates) {
    const std::size_t k = cand.index;
    // Bracket the root inside the switch's neighbours: f falls as the switch moves later.
    const double x0 = program[k].from_m;
    double lo = program[k - 1].from_m + 1e-6;
    double hi = (k + 1 < program.size() ? program[k + 1].from_m : length) - 1e-6;
    auto evaluate = [&](double x, physics::ControlProgram* trial_out,
                        physics::SimulationResult* sim_out) {
      physics::ControlProgram trial = program;
      trial[k].from_m = x;
      physics::SimulationResult sim = resimulate(trial);
      ++result.trim_iterations;
      const double f = error(sim);
      *trial_out = std::move(trial);
      *sim_out = std::move(sim);
      return f;
    };
    physics::ControlProgram trial;
    physics::SimulationResult sim;
    double f0 = error(run.sim);
    // Narrow the bracket to the side of x0 that holds the root, starting from the secant guess.
    double step = std::abs(f0 / cand.slope);
    double f_lo = NAN, f_hi = NAN;
    if (f0 > 0.0) {  // too slow: move later
      lo = x0;
      f_lo = f0;
      for (double x = x0 + 2.0 * step; x < hi; x = x0 + (x - x0) * 2.0) {
        const double f = evaluate(x, &trial, &sim);
        if (f <= 0.0) {
          hi = x;
          f_hi = f;
          break;
        }
        lo = x;
        f_lo = f;
      }
    } else {  // too fast: move earlier
      hi = x0;
      f_hi = f0;
      for (double x = x0 - 2.0 * step; x > lo; x = x0 - (x0 - x) * 2.0) {
        const double f = evaluate(x, &trial, &sim);
        if (f >= 0.0) {
          lo = x;
          f_lo = f;
          break;
        }
        hi = x;
        f_hi = f;
      }
    }
    if (std::isnan(f_lo)) f_lo = evaluate(lo, &trial, &sim);
    if (std::isnan(f_hi)) f_hi = evaluate(hi, &trial, &sim);
    if (!(f_lo >= 0.0 && f_hi <= 0.0)) continue;  // this switch cannot reach the target
    // Close the bracket with the one root search of the engine (LambdaBracket: Illinois regula
    // falsi), here in the switch position; only its own evaluations may be accepted.
    struct Last {
      bool valid = false;
      double x = 0.0, f = 0.0;
      physics::ControlProgram program;
      physics::SimulationResult sim;
    } last;
    LambdaBracket root(
        [&](double x) {
          last.f = evaluate(x, &last.program, &last.sim);
          last.x = x;
          last.valid = true;
          return last.f;
        },
        lo, f_lo, hi, f_hi, kTrimEvaluations);
    root.narrow([&] { return last.valid && std::abs(last.f) <= tolerance_s; }, kTrimMinWidth_m);
    if (last.valid && std::abs(last.f) <= tolerance_s) {
      const double cost = engine.energy_cost_J(last.sim);
      if (from_optimum && cost > along_frontier_J + kTrimExcessShare * gap_price_J +
                                     kTrimExcessFloor * base_cost_J) {
        continue;  // this switch buys the time far dearer than the price: try the next one
      }
      run.program = std::move(last.program);
      run.sim = std::move(last.sim);
      run.cost_J = cost;
      result.trim_shift_m = last.x - x0;
      return true;
    }
  }
  return false;
}

// The coarse trim: how many times the fine run may correct the coarse target, and the share of
// the tolerance the coarse trim aims at (the rest is room for the coarse-to-fine difference to
// change with the switch, which is far smaller: both runs step alike up to the switch).
constexpr int kCoarseTrimRounds = 3;
constexpr double kCoarseTrimShare = 0.25;
}  // namespace

bool trim_via_coarse_runs(const SectionEngine& engine, double target, double tolerance_s,
                          TimeSearchResult& result, double step_m, double offset_s,
                          physics::SimulationResult fine_base) {
  TimeSearchResult coarse = result;
  double shift_m = 0.0;
  for (int k = 0; k < kCoarseTrimRounds; ++k) {
    coarse.trim_iterations = 0;
    coarse.trim_shift_m = 0.0;
    const bool met = trim_at_step(engine, target - offset_s, kCoarseTrimShare * tolerance_s, coarse,
                                  step_m, true);
    result.trim_iterations += coarse.trim_iterations;
    if (!met) return false;
    shift_m += coarse.trim_shift_m;
    const LambdaRun& trial = coarse.run;
    physics::SimulationResult sim = fine_base.checkpoints.empty()
                                        ? engine.simulate(trial.program, trial.start)
                                        : engine.resimulate(trial.program, trial.start, fine_base);
    ++result.trim_iterations;
    if (!run_arrives(sim)) return false;
    if (std::abs(sim.running_time_s - target) <= tolerance_s) {
      result.run.program = trial.program;
      result.run.sim = std::move(sim);
      result.run.cost_J = engine.energy_cost_J(result.run.sim);
      result.run.kept.reset();
      result.trim_shift_m = shift_m;
      return true;
    }
    offset_s = sim.running_time_s - trial.sim.running_time_s;
    fine_base = std::move(sim);
  }
  return false;
}

bool trim_to_time(const SectionEngine& engine, double target, double tolerance_s,
                  TimeSearchResult& result, double search_step_m, bool from_optimum) {
  LambdaRun& run = result.run;
  if (run_arrives(run.sim) && std::abs(run.sim.running_time_s - target) <= tolerance_s) {
    return true;
  }
  const double fine_m = engine.options().resim_step_m;
  if (engine.searches_coarse(search_step_m) && from_optimum && run_arrives(run.sim)) {
    TimeSearchResult coarse = result;
    coarse.run.sim = engine.simulate(run.program, run.start, search_step_m);
    ++coarse.trim_iterations;
    const double offset_s = run.sim.running_time_s - coarse.run.sim.running_time_s;
    const bool met =
        trim_via_coarse_runs(engine, target, tolerance_s, coarse, search_step_m, offset_s, run.sim);
    result.trim_iterations = coarse.trim_iterations;
    if (met) {
      run = std::move(coarse.run);
      result.trim_shift_m = coarse.trim_shift_m;
      return true;
    }
  }
  // On fine runs (also when the coarse trim could not close the gap).
  return trim_at_step(engine, target, tolerance_s, result, fine_m, from_optimum);
}

}  // namespace ecorail::dp
