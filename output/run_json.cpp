#include "output/run_json.hpp"

#include "data/atomic_file.hpp"

#include "physics/units.hpp"

namespace ecorail::output {

nlohmann::json regimes_json(const std::vector<dp::RegimeSpan>& spans) {
  nlohmann::json list = nlohmann::json::array();
  for (const auto& r : spans) {
    list.push_back({{"regime", physics::regime_name(r.regime)},
                    {"speed_hold", r.speed_hold},
                    {"start_m", r.start_m},
                    {"end_m", r.end_m},
                    {"start_speed_kmh", units::ms_to_kmh(r.start_speed_ms)},
                    {"end_speed_kmh", units::ms_to_kmh(r.end_speed_ms)},
                    {"start_time_s", r.start_time_s},
                    {"end_time_s", r.end_time_s}});
  }
  return list;
}

double auxiliary_energy_kJ(const physics::Train& train, double on_line_s) {
  return units::J_to_kJ(train.auxiliary_power_W * on_line_s);
}

nlohmann::json run_json(const physics::SimulationResult& sim) {
  return run_json(sim, dp::regime_spans(sim.trace));
}

nlohmann::json run_json(const physics::SimulationResult& sim,
                        const std::vector<dp::RegimeSpan>& spans) {
  return {{"traction_energy_kJ", units::J_to_kJ(sim.energy.traction_work_J)},
          {"braking_energy_kJ", units::J_to_kJ(sim.energy.brake_work_J)},
          {"regen_energy_kJ", units::J_to_kJ(sim.energy.regen_J)},
          {"traction_input_energy_kJ", units::J_to_kJ(sim.energy.traction_input_J)},
          {"net_energy_kJ", units::J_to_kJ(sim.energy.net_J())},
          {"running_time_s", sim.running_time_s},
          {"stop_error_m", sim.stop_error_m},
          {"max_overspeed_kmh", units::ms_to_kmh(std::max(0.0, sim.max_overspeed_ms))},
          {"regimes", regimes_json(spans)}};
}

nlohmann::json section_solution_json(const dp::SectionSolution& solution) {
  const dp::SectionSolveSummary& s = solution.summary;
  nlohmann::json j = run_json(solution.run.sim, solution.regimes);
  j["from"] = s.from;
  j["to"] = s.to;
  j["distance_m"] = s.distance_m;
  j["target_time_s"] = s.target_time_s;
  j["min_running_time_s"] = s.min_time_s;
  j["lambda"] = s.lambda_J_per_s / 1000.0;
  j["lambda_unit"] = "kJ/s";
  j["objective"] = std::string(dp::objective_name(s.objective));
  j["converged"] = s.converged();
  j["termination"] = std::string(dp::termination_name(s.termination));
  j["warnings"] = s.warnings;
  j["grid"] = {{"ds_m", s.grid.ds_m},
               {"dv_kmh", s.grid.dv_kmh},
               {"substep_m", s.grid.substep_m},
               {"stages", s.stages},
               {"nodes", s.nodes}};
  // The polish's re-simulations whether or not its run replaced the grid's (a rejected polish
  // costs time too); "cruise_polish" below is there only when it did.
  j["search"] = {{"lambda_evaluations", s.lambda_evaluations},
                 {"trim_simulations", s.trim_simulations},
                 {"trim_shift_m", s.trim_shift_m},
                 {"cruise_polish_simulations", s.cruise_polish_simulations}};
  if (s.cruise_polished) {
    j["search"]["cruise_polish"] = {{"dropped_phases", s.cruise_dropped_phases},
                                    {"simulations", s.cruise_polish_simulations},
                                    {"saving_kJ", s.cruise_polish_saving_kJ}};
  }
  if (s.grid_cruises_searched) {
    j["search"]["grid_cruises"] = {{"kept", s.grid_cruises_kept},
                                   {"saving_kJ", s.grid_cruises_saving_kJ}};
  }
  if (s.min_regime.active()) {
    j["min_regime"] = {{"min_length_m", s.min_regime.min_length_m},
                       {"min_duration_s", s.min_regime.min_duration_s},
                       {"merged_phases", s.merged_regimes},
                       {"unmerged_energy_kJ", s.unmerged_energy_kJ},
                       {"cost_kJ", s.min_regime_cost_kJ}};
  }
  j["solve_wall_s"] = s.total_wall_s;
  j["threads"] = s.threads;
  return j;
}

void write_json(std::ostream& out, const nlohmann::json& document) {
  out << document.dump(2) << "\n";
}

void write_json(const std::filesystem::path& path, const nlohmann::json& document) {
  data::write_atomically(path, [&](std::ostream& out) { write_json(out, document); });
}

}  // namespace ecorail::output
