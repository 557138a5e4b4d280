#include "dp/time_target.hpp"

#include "dp/lambda_bracket.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

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
                                const TimeSearchOptions& options, const StartState& start) {
  const physics::SimulationResult flat_out = engine.min_time_run(start);
  if (flat_out.stopped_early) {
    throw std::invalid_argument("the train cannot reach the end of the section from this state");
  }
  const double t_min = flat_out.running_time_s;
  if (target < t_min - options.tolerance_s) throw InfeasibleTimeError(target, t_min);

  TimeSearchResult out;
  bool have_best = false;
  auto error_of_best = [&] { return std::abs(out.run.sim.running_time_s - target); };
  auto evaluate = [&](double x) {
    LambdaRun run = engine.run(std::exp(x), start);
    ++out.iterations;
    const double f = run.sim.running_time_s - target;
    if (!have_best || std::abs(f) < error_of_best()) {
      out.run = std::move(run);
      have_best = true;
    }
    return f;
  };
  auto trimmed = [&] {
    if (!options.trim) return false;
    TimeSearchResult attempt = out;
    if (!trim_to_time(engine, target, options.tolerance_s, attempt)) {
      out.trim_iterations = attempt.trim_iterations;
      return false;
    }
    out = std::move(attempt);
    return true;
  };

  LambdaBracket bracket(evaluate, std::log(options.lambda_guess), std::log(options.bracket_factor),
                        options.max_iterations);
  // First to the coarse tolerance, where the trim takes over; if the trim cannot close the gap,
  // on to the fine tolerance without it.
  const double phases[] = {options.trim ? options.lambda_tolerance_s : options.tolerance_s,
                           options.tolerance_s};
  for (double tolerance : phases) {
    bracket.narrow([&] { return error_of_best() <= tolerance; });
    if (error_of_best() <= options.tolerance_s || trimmed()) {
      out.converged = true;
      return out;
    }
  }
  out.converged = error_of_best() <= options.tolerance_s;
  return out;
}

bool trim_to_time(const SectionEngine& engine, double target, double tolerance_s,
                  TimeSearchResult& result) {
  LambdaRun& run = result.run;
  auto error = [&](const physics::SimulationResult& sim) { return sim.running_time_s - target; };
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
  constexpr double kProbe_m = 0.5;
  for (std::size_t k = 1; k < program.size(); ++k) {
    if (program[k - 1].control != physics::Control::MaxTraction) continue;
    const double hi = k + 1 < program.size() ? program[k + 1].from_m : length;
    if (program[k].from_m + kProbe_m >= hi) continue;
    physics::ControlProgram probe = program;
    probe[k].from_m += kProbe_m;
    const double slope = (error(engine.simulate(probe, run.start)) - error(run.sim)) / kProbe_m;
    ++result.trim_iterations;
    if (slope < 0.0) candidates.push_back({k, slope});
  }
  std::sort(candidates.begin(), candidates.end(),
            [](const Candidate& a, const Candidate& b) { return a.slope < b.slope; });

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
      physics::SimulationResult sim = engine.simulate(trial, run.start);
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
    // Illinois regula falsi on [lo, hi].
    int side = 0;
    for (int it = 0; it < 40; ++it) {
      double x = (lo * f_hi - hi * f_lo) / (f_hi - f_lo);
      if (!(x > lo && x < hi)) x = 0.5 * (lo + hi);
      const double f = evaluate(x, &trial, &sim);
      if (std::abs(f) <= tolerance_s) {
        run.program = std::move(trial);
        run.sim = std::move(sim);
        run.cost_J = engine.energy_cost_J(run.sim);
        result.trim_shift_m = x - x0;
        return true;
      }
      if (f > 0.0) {
        lo = x, f_lo = f;
        if (side == -1) f_hi *= 0.5;
        side = -1;
      } else {
        hi = x, f_hi = f;
        if (side == 1) f_lo *= 0.5;
        side = 1;
      }
      if (hi - lo < 1e-9) break;
    }
  }
  return false;
}

}  // namespace ecorail::dp
