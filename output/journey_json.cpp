#include "output/journey_json.hpp"

#include <cmath>

#include "output/run_json.hpp"
#include "physics/units.hpp"

namespace ecorail::output {

nlohmann::json journey_json(const dp::JourneySolution& sol, const JourneyLabels& labels) {
  nlohmann::json sections = nlohmann::json::array();
  nlohmann::json all_regimes = nlohmann::json::array();
  double distance = 0.0, worst_stop = 0.0, overspeed = 0.0, max_deviation = 0.0;
  for (std::size_t i = 0; i < sol.sections.size(); ++i) {
    const auto& sec = sol.sections[i];
    const auto& sim = sec.run.sim;
    const double length = sim.trace.empty() ? 0.0 : sim.trace.back().s_m;
    nlohmann::json j = run_json(sim, sec.regimes);
    j["from"] = labels.stops[i];
    j["to"] = labels.stops[i + 1];
    j["distance_m"] = length;
    j["min_running_time_s"] = sec.min_time_s;
    j["dwell_after_s"] = sec.dwell_after_s;
    if (std::isfinite(sec.marginal_J_per_s)) {
      j["marginal_energy_kJ_per_s"] = sec.marginal_J_per_s / 1000.0;
      if (std::isfinite(sol.lambda_J_per_s)) {
        const double dev = sec.marginal_J_per_s / sol.lambda_J_per_s - 1.0;
        j["marginal_vs_lambda"] = dev;
        max_deviation = std::max(max_deviation, std::abs(dev));
      }
    } else {
      j["marginal_energy_kJ_per_s"] = nullptr;
    }
    for (auto r : j["regimes"]) {
      r["section"] = i + 1;
      all_regimes.push_back(r);
    }
    sections.push_back(j);
    distance += length;
    worst_stop = std::max(worst_stop, std::abs(sim.stop_error_m));
    overspeed = std::max(overspeed, units::ms_to_kmh(std::max(0.0, sim.max_overspeed_ms)));
  }
  double dwell_total = 0.0;
  nlohmann::json dwells = nlohmann::json::array();
  for (std::size_t i = 0; i + 1 < sol.sections.size(); ++i) {
    dwells.push_back(
        {{"station", labels.stops[i + 1]}, {"dwell_s", sol.sections[i].dwell_after_s}});
    dwell_total += sol.sections[i].dwell_after_s;
  }
  nlohmann::json j = {{"from", labels.stops.front()},
                      {"to", labels.stops.back()},
                      {"stops", labels.stops},
                      {"split", labels.split},
                      {"traction_energy_kJ", units::J_to_kJ(sol.traction_work_J)},
                      {"braking_energy_kJ", units::J_to_kJ(sol.brake_work_J)},
                      {"regen_energy_kJ", units::J_to_kJ(sol.regen_J)},
                      {"net_energy_kJ", units::J_to_kJ(sol.net_J)},
                      {"running_time_s", sol.running_time_s},
                      {"target_time_s", sol.target_time_s},
                      {"trip_time_s", sol.running_time_s + dwell_total},
                      {"distance_m", distance},
                      {"stop_error_m", worst_stop},
                      {"max_overspeed_kmh", overspeed},
                      {"section_times_s", nlohmann::json::array()},
                      {"sections", sections},
                      {"dwells", dwells},
                      {"regimes", all_regimes},
                      {"converged", sol.converged()},
                      {"termination", std::string(dp::termination_name(sol.summary.termination))},
                      {"warnings", sol.warnings},
                      {"grid", {{"ds_m", labels.ds_m}, {"dv_kmh", labels.dv_kmh}}},
                      {"search", {{"lambda_evaluations", sol.lambda_evaluations}}},
                      {"solve_wall_s", sol.total_wall_s},
                      {"threads", labels.threads}};
  for (const auto& s : sol.sections) j["section_times_s"].push_back(s.run.sim.running_time_s);
  if (std::isfinite(sol.lambda_J_per_s)) {
    j["lambda"] = sol.lambda_J_per_s / 1000.0;
    j["lambda_unit"] = "kJ/s";
    j["equal_lambda"] = {{"lambda_kJ_per_s", sol.lambda_J_per_s / 1000.0},
                         {"max_relative_deviation", max_deviation}};
  } else {
    j["lambda"] = nullptr;
  }
  return j;
}

}  // namespace ecorail::output
