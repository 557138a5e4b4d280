#include "dp/frontier.hpp"

#include <cmath>
#include <stdexcept>

#include "dp/text_format.hpp"
#include "dp/threads.hpp"
#include "physics/units.hpp"

namespace ecorail::dp {

bool FrontierOptions::IsValid(std::string* error) const {
  auto fail = [&](const char* why) {
    if (error) *error = why;
    return false;
  };
  if (!(t_min_s >= 0.0 && std::isfinite(t_min_s))) {
    return fail("t_min_s must be a running time >= 0 s (0: the minimum)");
  }
  if (!(t_max_s >= 0.0 && std::isfinite(t_max_s))) {
    return fail("t_max_s must be a running time >= 0 s (0: minimum + 60 s)");
  }
  if (t_max_s > 0.0 && t_max_s < t_min_s) return fail("t_max_s must not be below t_min_s");
  if (!(step_s > 0.0 && std::isfinite(step_s))) return fail("step_s must be a step in s > 0");
  // Each point is a solve of about 0.1 s: bound the count before any work, not after hours.
  const double span_s = t_max_s > 0.0 ? t_max_s - t_min_s : 60.0;
  if (span_s / step_s > kMaxFrontierPoints) {
    return fail("the frontier would have more than 10000 points: raise step_s or lower t_max_s");
  }
  if (!(convexity_tolerance >= 0.0 && std::isfinite(convexity_tolerance))) {
    return fail("convexity_tolerance must be a finite number >= 0");
  }
  return search.IsValid(error);
}

FrontierSummary summarize_frontier(const Frontier& f, const std::string& from,
                                   const std::string& to) {
  FrontierSummary s;
  s.from = from;
  s.to = to;
  s.min_time_s = f.min_time_s;
  s.points = static_cast<int>(f.points.size());
  for (const FrontierPoint& p : f.points) {
    s.converged_points += p.converged ? 1 : 0;
    s.evaluations += p.evaluations;
  }
  if (!f.points.empty()) {
    s.t_first_s = f.points.front().running_time_s;
    s.t_last_s = f.points.back().running_time_s;
    s.first_energy_kJ = units::J_to_kJ(f.points.front().cost_J);
    s.last_energy_kJ = units::J_to_kJ(f.points.back().cost_J);
  }
  s.monotone = f.monotone;
  s.convex = f.convex;
  for (const FrontierWobble& w : f.wobbles) {
    s.warnings.push_back(format_text("%s at %.1f s by %.3f kJ (grid effect)", w.kind.c_str(),
                                     w.time_s, units::J_to_kJ(w.size_J)));
  }
  if (s.converged_points < s.points) {
    s.warnings.push_back(format_text("%d of %d points missed their running time",
                                     s.points - s.converged_points, s.points));
  }
  s.termination = s.points == 0                    ? Termination::FAILURE
                  : s.converged_points == s.points ? Termination::CONVERGENCE
                                                   : Termination::NO_CONVERGENCE;
  return s;
}

std::string FrontierSummary::BriefReport() const {
  return format_text(
      "ecorail frontier %s -> %s: %d points from %.3f s to %.3f s (minimum %.3f s), %.1f kJ to "
      "%.1f kJ, %s\n",
      from.c_str(), to.c_str(), points, t_first_s, t_last_s, min_time_s, first_energy_kJ,
      last_energy_kJ, std::string(status_word(termination, warnings.size())).c_str());
}

std::string FrontierSummary::FullReport() const {
  std::string r = "\necorail frontier report\n\n";
  r += format_text("  %-28s %s -> %s\n", "Section", from.c_str(), to.c_str());
  r += format_text("  %-28s %.3f s\n", "Minimum running time", min_time_s);
  r += format_text("  %-28s %d (%d met their time), %.3f s to %.3f s\n", "Points", points,
                   converged_points, t_first_s, t_last_s);
  r +=
      format_text("  %-28s %d lambda evaluations and trim re-simulations\n", "Search", evaluations);
  r += format_text("  %-28s %.3f kJ to %.3f kJ\n", "Energy", first_energy_kJ, last_energy_kJ);
  r += format_text("  %-28s %s, %s\n", "Shape", monotone ? "monotone" : "NOT monotone",
                   convex ? "convex" : "NOT convex");
  r += format_text("\n  %-28s %s\n", "Termination",
                   std::string(termination_name(termination)).c_str());
  for (const auto& w : warnings) r += "  warning: " + w + "\n";
  return r;
}

Frontier compute_frontier(const SectionEngine& engine, const FrontierOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw std::invalid_argument(why);
  const ThreadScope threads(engine.options().threads);
  Frontier f;
  const physics::SimulationResult flat_out = engine.min_time_run();
  f.min_time_s = flat_out.running_time_s;
  // A first time below the flat-out run is refused, never moved up silently.
  if (options.t_min_s > 0.0 && options.t_min_s < f.min_time_s - 1e-9) {
    throw InfeasibleTimeError(options.t_min_s, f.min_time_s);
  }
  const double t_min = std::max(options.t_min_s, f.min_time_s);
  const double t_max = options.t_max_s > 0.0 ? options.t_max_s : f.min_time_s + 60.0;
  if (!(options.step_s > 0.0)) throw std::invalid_argument("frontier step must be positive");
  if (t_max < t_min) throw InfeasibleTimeError(t_max, f.min_time_s);

  auto add = [&](double target, const physics::SimulationResult& sim, double lambda, bool ok,
                 int evaluations) {
    f.points.push_back({target, sim.running_time_s, sim.energy.traction_work_J, sim.energy.regen_J,
                        sim.energy.net_J(), engine.energy_cost_J(sim), lambda, ok, evaluations});
  };
  LatticeRuns lattice;
  double t = t_min;
  if (t_min <= f.min_time_s + 1e-9) {
    // The minimum itself is the flat-out run (lambda infinite); go on from the next step.
    add(f.min_time_s, flat_out, INFINITY, true, 1);
    t = std::floor(f.min_time_s / options.step_s + 1.0) * options.step_s;
  }
  const int total = static_cast<int>(std::floor((t_max + 1e-9 - t) / options.step_s)) + 1;
  for (int k = 0; t <= t_max + 1e-9; t += options.step_s, ++k) {
    // No warm start from the previous point: each point is the stand-alone solve of its time.
    const TimeSearchResult r = solve_for_time(engine, t, options.search, {}, &lattice);
    add(t, r.run.sim, r.run.lambda, r.converged, r.iterations + r.trim_iterations);
    report_progress(options.progress, "point", k + 1, total);
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
