#include "dp/section_solve.hpp"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "dp/text_format.hpp"
#include "dp/threads.hpp"
#include "physics/energy_balance.hpp"
#include "physics/units.hpp"

namespace ecorail::dp {

bool run_meets_targets(const physics::SimulationResult& sim, double target_time_s) {
  return run_arrives(sim) &&
         (target_time_s <= 0.0 || std::abs(sim.running_time_s - target_time_s) <= kTimeTolerance_s);
}

void summarise_run(const physics::SimulationResult& sim, double target_time_s,
                   SectionSolveSummary& s) {
  s.running_time_s = sim.running_time_s;
  s.traction_energy_kJ = units::J_to_kJ(sim.energy.traction_work_J);
  s.braking_energy_kJ = units::J_to_kJ(sim.energy.brake_work_J);
  s.regen_energy_kJ = units::J_to_kJ(sim.energy.regen_J);
  s.net_energy_kJ = units::J_to_kJ(sim.energy.net_J());
  s.stop_error_m = sim.stop_error_m;
  s.max_overspeed_kmh = units::ms_to_kmh(std::max(0.0, sim.max_overspeed_ms));
  if (sim.stopped_early) {
    s.warnings.push_back(
        format_text("the train came to rest %.2f m before the station", -sim.stop_error_m));
  }
  if (std::abs(sim.stop_error_m) > 0.5) {
    s.warnings.push_back(format_text("stop error %.2f m exceeds 0.5 m", sim.stop_error_m));
  }
  if (s.max_overspeed_kmh > 0.05) {
    s.warnings.push_back(format_text("speed limit exceeded by %.3f km/h", s.max_overspeed_kmh));
  }
  if (target_time_s > 0.0 && std::abs(sim.running_time_s - target_time_s) > 0.1) {
    s.warnings.push_back(
        format_text("running time %.3f s misses the target %.3f s by more than 0.1 s",
                    sim.running_time_s, target_time_s));
  }
}

SectionSolution solve_section(const physics::Train& train, const physics::Route& route,
                              double target_time_s, const SectionSolveOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw std::invalid_argument(why);
  const ThreadScope threads(options.engine.threads);
  const auto t0 = std::chrono::steady_clock::now();
  SectionEngine engine(train, route, options.engine);
  const auto t1 = std::chrono::steady_clock::now();
  TimeSearchResult found = solve_for_time(engine, target_time_s, options.search);
  const auto t2 = std::chrono::steady_clock::now();

  SectionSolution out;
  // A minimum regime merges short phases and trims the run back to the target.
  MinRegimeResult merged = enforce_min_regime(engine, found.run, target_time_s, options.min_regime);
  out.run = std::move(merged.run);
  out.regimes = regime_spans(out.run.sim.trace, std::max(0.5, options.min_regime.min_length_m));
  SectionSolveSummary& s = out.summary;
  s.from = route.from_name();
  s.to = route.to_name();
  s.distance_m = route.length_m();
  s.target_time_s = target_time_s;
  s.min_time_s = engine.min_time_run().running_time_s;
  s.grid = options.engine.grid;
  s.stages = engine.grid().stage_count();
  s.nodes = engine.grid().total_nodes();
  s.threads = omp_get_max_threads();
  s.objective = options.engine.objective;
  s.lambda_J_per_s = out.run.lambda;
  s.lambda_evaluations = found.iterations;
  s.trim_simulations = found.trim_iterations;
  s.trim_shift_m = found.trim_shift_m;
  s.cruise_polished = found.cruise_polish.applied;
  s.cruise_dropped_phases = found.cruise_polish.applied ? found.cruise_polish.dropped_phases : 0;
  s.cruise_polish_simulations = found.cruise_polish.simulations;
  s.cruise_polish_saving_kJ =
      units::J_to_kJ(found.cruise_polish.cost_before_J - found.cruise_polish.cost_after_J);
  s.grid_cruises_searched = found.grid_cruises_searched;
  s.grid_cruises_kept = found.grid_cruises_kept;
  s.grid_cruises_saving_kJ = units::J_to_kJ(found.grid_cruises_saving_J);
  s.build_wall_s = std::chrono::duration<double>(t1 - t0).count();
  s.search_wall_s = std::chrono::duration<double>(t2 - t1).count();
  s.total_wall_s = std::chrono::duration<double>(t2 - t0).count();
  summarise_run(out.run.sim, target_time_s, s);
  s.min_regime = options.min_regime;
  s.merged_regimes = merged.merged_entries;
  s.unmerged_energy_kJ = units::J_to_kJ(merged.cost_before_J);
  s.min_regime_cost_kJ = units::J_to_kJ(merged.cost_after_J - merged.cost_before_J);
  if (merged.short_entries_left > 0) {
    s.warnings.push_back(format_text("%d control phases remain below the minimum regime",
                                     merged.short_entries_left));
  }
  // A run that misses its stop or its time is never a converged result, whatever the search
  // reported (see SectionSolveSummary::IsSolutionUsable).
  // Nor is a run whose energy does not balance (input that slipped past validation).
  const physics::EnergyBalance balance = physics::energy_balance(engine.motion(), out.run.sim);
  if (!balance.closes()) {
    s.warnings.push_back(format_text(
        "energy does not balance: traction %.1f kJ - braking %.1f kJ - resistance %.1f kJ - "
        "kinetic %.1f kJ = %.1f kJ (tolerance %.1f kJ), dissipation %.1f kJ",
        balance.traction_work_J / 1e3, balance.brake_work_J / 1e3, balance.resistance_work_J / 1e3,
        balance.kinetic_change_J / 1e3, balance.residual_J / 1e3, balance.tolerance_J / 1e3,
        balance.dissipation_J / 1e3));
  }
  s.termination = termination_of(
      run_arrives(out.run.sim),
      found.converged && run_meets_targets(out.run.sim, target_time_s) && balance.closes());
  if (!found.converged) {
    s.warnings.push_back(
        format_text("running-time search did not converge to %.3f s", options.search.tolerance_s));
  }
  return out;
}

std::string SectionSolveSummary::BriefReport() const {
  std::string r = format_text(
      "ecorail solve %s -> %s (%.1f m) in %.3f s: traction %.1f kJ, regenerated %.1f kJ, "
      "stop error %.3f m, max overspeed %.3f km/h; lambda %s, %d lambda evaluations, "
      "%.3f s wall, %s",
      from.c_str(), to.c_str(), distance_m, running_time_s, traction_energy_kJ, regen_energy_kJ,
      stop_error_m, max_overspeed_kmh, lambda_text(lambda_J_per_s).c_str(), lambda_evaluations,
      total_wall_s, std::string(status_word(termination, warnings.size())).c_str());
  return r + "\n" + min_regime_text();
}

std::string SectionSolveSummary::min_regime_text() const {
  if (!min_regime.active()) return "";
  return format_text(
      "  minimum regime %.0f m / %.0f s: %d phases merged, energy %+.1f kJ (%+.4f %%) against "
      "the unmerged optimum of %.1f kJ\n",
      min_regime.min_length_m, min_regime.min_duration_s, merged_regimes, min_regime_cost_kJ,
      unmerged_energy_kJ > 0.0 ? 100.0 * min_regime_cost_kJ / unmerged_energy_kJ : 0.0,
      unmerged_energy_kJ);
}

std::string SectionSolveSummary::FullReport() const {
  std::string r = "\necorail section solver report\n\n";
  r += format_text("  %-28s %s -> %s\n", "Section", from.c_str(), to.c_str());
  r += format_text("  %-28s %.1f m\n", "Distance", distance_m);
  r += format_text("  %-28s %.3f s (minimum %.3f s)\n", "Target running time", target_time_s,
                   min_time_s);
  r += format_text(
      "  %-28s %s\n", "Objective",
      objective == Objective::Net ? "net energy (traction - regenerated)" : "traction energy");
  r += format_text("  %-28s ds %.3g m, dv %.3g km/h, substep %.3g m\n", "Grid", grid.ds_m,
                   grid.dv_kmh, grid.substep_m);
  r += format_text("  %-28s %d stages, %d nodes\n", "", stages, nodes);
  r += format_text("  %-28s %d\n", "Threads", threads);
  r += format_text("  %-28s %s\n", "Lambda (time price)", lambda_text(lambda_J_per_s).c_str());
  r += format_text("  %-28s %d lambda evaluations, %d trim re-simulations (shift %.3f m)\n",
                   "Search", lambda_evaluations, trim_simulations, trim_shift_m);
  if (cruise_polished) {
    r += format_text(
        "  %-28s one hold, %d short phases dropped, %d re-simulations, %.1f kJ saved\n",
        "Cruise polish", cruise_dropped_phases, cruise_polish_simulations, cruise_polish_saving_kJ);
  }
  if (grid_cruises_searched) {
    r += format_text("  %-28s %s\n", "Grid's own cruises",
                     grid_cruises_kept ? format_text("kept, %.1f kJ cheaper than the held ones",
                                                     grid_cruises_saving_kJ)
                                             .c_str()
                                       : "searched, not cheaper than the held ones");
  }
  r += format_text("  %-28s %.4f s build, %.4f s search, %.4f s total\n", "Wall time", build_wall_s,
                   search_wall_s, total_wall_s);
  r += min_regime_text();
  r += result_block_text({running_time_s, traction_energy_kJ, braking_energy_kJ, regen_energy_kJ,
                          net_energy_kJ, "Stop error", stop_error_m, max_overspeed_kmh, termination,
                          &warnings});
  return r;
}

}  // namespace ecorail::dp
