#include "dp/journey.hpp"

#include "dp/lambda_bracket.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

namespace ecorail::dp {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// Every section's run for one lambda. Sections are independent, so they run side by side
// (each one's sweep then runs on the thread it is given); results do not depend on which thread
// ran which section.
std::vector<LambdaRun> run_all(const std::vector<std::unique_ptr<SectionEngine>>& engines,
                               double lambda) {
  std::vector<LambdaRun> runs(engines.size());
  const int n = static_cast<int>(engines.size());
#pragma omp parallel for schedule(dynamic, 1)
  for (int i = 0; i < n; ++i) runs[i] = engines[i]->run(lambda);
  return runs;
}

double total_time(const std::vector<LambdaRun>& runs) {
  double t = 0.0;
  for (const auto& r : runs) t += r.sim.running_time_s;
  return t;
}

// Optimal split: regula falsi on log(lambda) for the total time, then a trim of one section.
void optimal_split(const std::vector<std::unique_ptr<SectionEngine>>& engines, double target,
                   const TimeSearchOptions& opt, JourneySolution& out,
                   std::vector<LambdaRun>& best) {
  double best_err = INFINITY;
  auto evaluate = [&](double x) {
    std::vector<LambdaRun> runs = run_all(engines, std::exp(x));
    ++out.lambda_evaluations;
    const double f = total_time(runs) - target;
    if (std::abs(f) < best_err) {
      best_err = std::abs(f);
      best = std::move(runs);
      out.lambda_J_per_s = std::exp(x);
    }
    return f;
  };
  LambdaBracket bracket(evaluate, std::log(opt.lambda_guess), std::log(opt.bracket_factor),
                        opt.max_iterations);
  const double coarse = opt.trim ? opt.lambda_tolerance_s : opt.tolerance_s;
  bracket.narrow([&] { return best_err <= coarse; });
  // Close the rest on one section, the longest-running first (it has the most room to move);
  // if no section can, narrow lambda to the fine tolerance instead.
  if (best_err <= opt.tolerance_s) {
    out.converged = true;
    return;
  }
  const double residual = total_time(best) - target;
  std::vector<std::size_t> order(best.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return best[a].sim.running_time_s > best[b].sim.running_time_s;
  });
  for (std::size_t i : opt.trim ? order : std::vector<std::size_t>{}) {
    TimeSearchResult r;
    r.run = best[i];
    if (trim_to_time(*engines[i], best[i].sim.running_time_s - residual, opt.tolerance_s, r)) {
      best[i] = std::move(r.run);
      out.converged = true;
      return;
    }
  }
  bracket.narrow([&] { return best_err <= opt.tolerance_s; });
  out.converged = best_err <= opt.tolerance_s;
}

}  // namespace

JourneySolution solve_journey(const physics::Train& train,
                              const std::vector<physics::Route>& routes,
                              const std::vector<double>& dwells_s, double total_time_s,
                              const JourneyOptions& options) {
  const auto t0 = Clock::now();
  JourneySolution out;
  out.target_time_s = total_time_s;
  std::vector<std::unique_ptr<SectionEngine>> engines;
  double min_total = 0.0, length = 0.0;
  std::vector<double> min_times;
  for (const auto& route : routes) {
    engines.push_back(std::make_unique<SectionEngine>(train, route, options.engine));
    min_times.push_back(engines.back()->min_time_run().running_time_s);
    min_total += min_times.back();
    length += route.length_m();
  }
  out.build_wall_s = seconds_since(t0);
  if (total_time_s < min_total - options.search.tolerance_s) {
    throw InfeasibleTimeError(total_time_s, min_total);
  }

  const auto t1 = Clock::now();
  std::vector<LambdaRun> runs;
  if (options.split == Split::Optimal) {
    optimal_split(engines, total_time_s, options.search, out, runs);
  } else {
    out.lambda_J_per_s = NAN;
    out.converged = true;
    for (std::size_t i = 0; i < engines.size(); ++i) {
      const double share = total_time_s * routes[i].length_m() / length;
      if (share < min_times[i]) {
        char msg[300];
        std::snprintf(msg, sizeof msg,
                      "the proportional share %.2f s of section %s -> %s is below its minimum "
                      "running time %.2f s",
                      share, routes[i].from_name().c_str(), routes[i].to_name().c_str(),
                      min_times[i]);
        throw std::invalid_argument(msg);
      }
      TimeSearchResult r = solve_for_time(*engines[i], share, options.search);
      out.lambda_evaluations += r.iterations;
      out.converged = out.converged && r.converged;
      runs.push_back(std::move(r.run));
    }
  }
  out.search_wall_s = seconds_since(t1);

  for (std::size_t i = 0; i < runs.size(); ++i) {
    JourneySection sec;
    sec.run = std::move(runs[i]);
    sec.regimes = regime_spans(sec.run.sim.trace);
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
    // -(dE/dT) by central difference of two fresh solves of the section alone.
    const double h = options.marginal_step_s;
    const int n = static_cast<int>(out.sections.size());
#pragma omp parallel for schedule(dynamic, 1)
    for (int i = 0; i < n; ++i) {
      const double t = out.sections[i].run.sim.running_time_s;
      if (t - h < min_times[i]) continue;
      const auto slow = solve_for_time(*engines[i], t + h, options.search);
      const auto fast = solve_for_time(*engines[i], t - h, options.search);
      out.sections[i].marginal_J_per_s =
          (engines[i]->energy_cost_J(fast.run.sim) - engines[i]->energy_cost_J(slow.run.sim)) /
          (slow.run.sim.running_time_s - fast.run.sim.running_time_s);
    }
  }
  if (!out.converged) {
    out.warnings.push_back("total running time not met to " +
                           std::to_string(options.search.tolerance_s) + " s");
  }
  out.total_wall_s = seconds_since(t0);
  return out;
}

}  // namespace ecorail::dp
