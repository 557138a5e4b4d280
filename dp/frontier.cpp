#include "dp/frontier.hpp"

#include <cmath>

namespace ecorail::dp {

Frontier compute_frontier(const SectionEngine& engine, const FrontierOptions& options) {
  Frontier f;
  const physics::SimulationResult flat_out = engine.min_time_run();
  f.min_time_s = flat_out.running_time_s;
  const double t_min = std::max(options.t_min_s, f.min_time_s);
  const double t_max = options.t_max_s > 0.0 ? options.t_max_s : f.min_time_s + 60.0;
  if (!(options.step_s > 0.0)) throw std::invalid_argument("frontier step must be positive");
  if (t_max < t_min) throw InfeasibleTimeError(t_max, f.min_time_s);

  auto add = [&](double target, const physics::SimulationResult& sim, double lambda, bool ok,
                 int evaluations) {
    f.points.push_back({target, sim.running_time_s, sim.energy.traction_work_J, sim.energy.regen_J,
                        sim.energy.net_J(), engine.energy_cost_J(sim), lambda, ok, evaluations});
  };
  TimeSearchOptions search = options.search;
  double t = t_min;
  if (t_min <= f.min_time_s + 1e-9) {
    // The minimum itself is the flat-out run (lambda infinite); go on from the next step.
    add(f.min_time_s, flat_out, INFINITY, true, 1);
    t = std::floor(f.min_time_s / options.step_s + 1.0) * options.step_s;
  }
  for (; t <= t_max + 1e-9; t += options.step_s) {
    // Warm start: extrapolate log(lambda) linearly in time from the last two points, and
    // bracket in small steps around the prediction.
    const std::size_t n = f.points.size();
    if (n >= 2 && std::isfinite(f.points[n - 2].lambda_J_per_s)) {
      const auto& a = f.points[n - 2];
      const auto& b = f.points[n - 1];
      const double slope = (std::log(b.lambda_J_per_s) - std::log(a.lambda_J_per_s)) /
                           (b.running_time_s - a.running_time_s);
      search.lambda_guess = std::exp(std::log(b.lambda_J_per_s) + slope * (t - b.running_time_s));
      search.bracket_factor = 1.15;
      search.lambda_tolerance_s = std::max(search.lambda_tolerance_s, 0.25 * options.step_s);
    }
    const TimeSearchResult r = solve_for_time(engine, t, search);
    add(t, r.run.sim, r.run.lambda, r.converged, r.iterations + r.trim_iterations);
    search.lambda_guess = r.run.lambda;
  }
  check_frontier_shape(f, options.convexity_tolerance);
  return f;
}

void check_frontier_shape(Frontier& f, double tolerance) {
  f.wobbles.clear();
  f.monotone = f.convex = true;
  const auto& p = f.points;
  for (std::size_t k = 1; k < p.size(); ++k) {
    if (p[k].cost_J >= p[k - 1].cost_J) {
      f.monotone = false;
      f.wobbles.push_back({p[k].target_time_s, "non_monotone", p[k].cost_J - p[k - 1].cost_J});
    }
  }
  for (std::size_t k = 1; k + 1 < p.size(); ++k) {
    const double left =
        (p[k].cost_J - p[k - 1].cost_J) / (p[k].running_time_s - p[k - 1].running_time_s);
    const double right =
        (p[k + 1].cost_J - p[k].cost_J) / (p[k + 1].running_time_s - p[k].running_time_s);
    // Convex: slopes rise. Measure the shortfall as an energy over the right-hand step.
    const double shortfall = (left - right) * (p[k + 1].running_time_s - p[k].running_time_s);
    if (shortfall > tolerance * std::abs(p[k].cost_J)) {
      f.convex = false;
      f.wobbles.push_back({p[k].target_time_s, "non_convex", shortfall});
    }
  }
}

}  // namespace ecorail::dp
