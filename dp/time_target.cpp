#include "dp/time_target.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace ecorail::dp {

namespace {
std::string infeasible_message(double requested, double minimum) {
  char buf[200];
  std::snprintf(buf, sizeof buf,
                "running time %.2f s is below the minimum running time of %.2f s for this "
                "section (flat-out run)",
                requested, minimum);
  return buf;
}
}  // namespace

InfeasibleTimeError::InfeasibleTimeError(double requested_s, double minimum_s)
    : std::invalid_argument(infeasible_message(requested_s, minimum_s)), minimum_s_(minimum_s) {}

TimeSearchResult solve_for_time(const SectionEngine& engine, double target,
                                const TimeSearchOptions& options) {
  const double t_min = engine.min_time_run().running_time_s;
  if (target < t_min - options.tolerance_s) throw InfeasibleTimeError(target, t_min);

  TimeSearchResult out;
  auto finish = [&](TimeSearchResult& r) -> TimeSearchResult& {
    if (options.trim) {
      r.converged = trim_to_time(engine, target, options.tolerance_s, r);
    } else {
      r.converged = std::abs(r.run.sim.running_time_s - target) <= options.tolerance_s;
    }
    return r;
  };
  const double coarse = options.trim ? options.lambda_tolerance_s : options.tolerance_s;
  bool have_best = false;
  auto evaluate = [&](double x) {
    LambdaRun run = engine.run(std::exp(x));
    ++out.iterations;
    const double f = run.sim.running_time_s - target;
    if (!have_best || std::abs(f) < std::abs(out.run.sim.running_time_s - target)) {
      out.run = run;
      have_best = true;
    }
    return f;
  };

  // Bracket: f(lo) > 0 (too slow), f(hi) < 0 (too fast), in x = log(lambda).
  double x = std::log(options.lambda_guess);
  double f = evaluate(x);
  double x_lo = x, f_lo = f, x_hi = x, f_hi = f;
  const double step = std::log(4.0);
  while (f_lo < 0.0 && out.iterations < options.max_iterations && x_lo > std::log(1.0)) {
    x_hi = x_lo;
    f_hi = f_lo;
    x_lo -= step;
    f_lo = evaluate(x_lo);
  }
  while (f_hi > 0.0 && out.iterations < options.max_iterations && x_hi < std::log(1e12)) {
    x_lo = x_hi;
    f_lo = f_hi;
    x_hi += step;
    f_hi = evaluate(x_hi);
  }
  if (std::abs(out.run.sim.running_time_s - target) <= coarse) return finish(out);
  if (f_lo < 0.0 || f_hi > 0.0) return finish(out);  // could not bracket

  // Illinois regula falsi on the bracket.
  int side = 0;
  while (out.iterations < options.max_iterations && x_hi - x_lo > 1e-13) {
    double xm = (x_lo * f_hi - x_hi * f_lo) / (f_hi - f_lo);
    if (!(xm > x_lo && xm < x_hi)) xm = 0.5 * (x_lo + x_hi);
    const double fm = evaluate(xm);
    if (std::abs(fm) <= coarse) return finish(out);
    if (fm > 0.0) {
      x_lo = xm;
      f_lo = fm;
      if (side == -1) f_hi *= 0.5;
      side = -1;
    } else {
      x_hi = xm;
      f_hi = fm;
      if (side == 1) f_lo *= 0.5;
      side = 1;
    }
  }
  return finish(out);
}

bool trim_to_time(const SectionEngine& engine, double target, double tolerance_s,
                  TimeSearchResult& result) {
  LambdaRun& run = result.run;
  auto error = [&](const physics::SimulationResult& sim) { return sim.running_time_s - target; };
  if (std::abs(error(run.sim)) <= tolerance_s) return true;
  const physics::ControlProgram& program = run.program;
  const double length = engine.route().length_m();
  // Candidate switch points: the ends of full-traction phases. Pick the one whose shift moves
  // the running time most (a switch held on the speed envelope barely moves it).
  std::size_t best = 0;
  double best_slope = 0.0;
  constexpr double kProbe_m = 0.5;
  for (std::size_t k = 1; k < program.size(); ++k) {
    if (program[k - 1].control != physics::Control::MaxTraction) continue;
    const double hi = k + 1 < program.size() ? program[k + 1].from_m : length;
    if (program[k].from_m + kProbe_m >= hi) continue;
    physics::ControlProgram probe = program;
    probe[k].from_m += kProbe_m;
    const double slope = (error(engine.simulate(probe)) - error(run.sim)) / kProbe_m;
    ++result.trim_iterations;
    if (slope < best_slope) {
      best_slope = slope;
      best = k;
    }
  }
  if (best == 0) return false;
  // Secant on the switch position, kept inside its neighbours.
  const double lo = program[best - 1].from_m + 1e-6;
  const double hi = (best + 1 < program.size() ? program[best + 1].from_m : length) - 1e-6;
  const double x0 = program[best].from_m;
  double x = x0, f = error(run.sim), slope = best_slope;
  for (int it = 0; it < 12; ++it) {
    const double x_new = std::clamp(x - f / slope, lo, hi);
    physics::ControlProgram trial = run.program;
    trial[best].from_m = x_new;
    physics::SimulationResult sim = engine.simulate(trial);
    ++result.trim_iterations;
    const double f_new = error(sim);
    if (x_new != x && f_new != f) slope = (f_new - f) / (x_new - x);
    x = x_new;
    f = f_new;
    run.program = std::move(trial);
    run.sim = std::move(sim);
    run.cost_J = engine.energy_cost_J(run.sim);
    if (std::abs(f) <= tolerance_s) break;
    if (!(slope < 0.0)) break;
  }
  result.trim_shift_m = x - x0;
  return std::abs(f) <= tolerance_s;
}

}  // namespace ecorail::dp
