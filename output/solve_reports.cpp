#include "output/solve_reports.hpp"

#include <algorithm>
#include <cmath>

#include "dp/text_format.hpp"
#include "output/provenance.hpp"
#include "output/run_json.hpp"
#include "physics/units.hpp"

namespace ecorail::output {

namespace {

nlohmann::json bound_or_null(double v) {
  return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
}
nlohmann::json kmh_or_null(double v_ms) {
  return std::isfinite(v_ms) ? nlohmann::json(units::ms_to_kmh(v_ms)) : nlohmann::json(nullptr);
}

nlohmann::json windows_json(const dp::TimingJourneySolution& sol) {
  nlohmann::json list = nlohmann::json::array();
  for (const auto& w : sol.windows) {
    nlohmann::json binds;
    if (w.binds.empty()) {
      binds = nullptr;
    } else if (w.binds.size() == 1) {
      binds = w.binds.front();
    } else {
      binds = w.binds;
    }
    list.push_back({{"position_m", w.window.position_m},
                    {"earliest_s", bound_or_null(w.window.earliest_s)},
                    {"latest_s", bound_or_null(w.window.latest_s)},
                    {"min_speed_kmh", kmh_or_null(w.window.min_speed_ms)},
                    {"max_speed_kmh", kmh_or_null(w.window.max_speed_ms)},
                    {"time_s", bound_or_null(w.time_s)},
                    {"speed_kmh", kmh_or_null(w.speed_ms)},
                    {"met", w.met},
                    {"binds", binds}});
  }
  return list;
}

nlohmann::json notes_json(const std::string& cap_note) {
  return cap_note.empty() ? nlohmann::json::array() : nlohmann::json::array({cap_note});
}

}  // namespace

nlohmann::json run_provenance_json(const data::Line& line, const physics::Train& train,
                                   const RunInputs& inputs, const nlohmann::json& extra_options) {
  nlohmann::json opts = {{"line", inputs.line},
                         {"train", inputs.train},
                         {"from", inputs.from},
                         {"to", inputs.to},
                         {"objective", inputs.objective}};
  for (const auto& [key, value] : extra_options.items()) opts[key] = value;
  return provenance_json(line, train, {{"ds_m", inputs.ds_m}, {"dv_kmh", inputs.dv_kmh}}, opts);
}

std::string speed_cap_note(const data::Line& line, const std::vector<std::string>& stops,
                           const physics::Train& train) {
  const data::Station* a = line.find_station(stops.front());
  const data::Station* b = line.find_station(stops.back());
  if (a == nullptr || b == nullptr) return "";
  const double lo = std::min(a->km_post_m, b->km_post_m), hi = std::max(a->km_post_m, b->km_post_m);
  const double vmax_kmh = units::ms_to_kmh(train.max_speed_ms);
  double highest_kmh = 0.0;
  for (const auto& r : line.limits) {
    const double r_lo = std::min(r.start_km_post_m, r.end_km_post_m);
    const double r_hi = std::max(r.start_km_post_m, r.end_km_post_m);
    if (r_hi > lo && r_lo < hi && r.value > vmax_kmh + 1e-9)
      highest_kmh = std::max(highest_kmh, r.value);
  }
  if (highest_kmh == 0.0) return "";
  return dp::format_text(
      "line limits up to %.1f km/h are above the train's maximum speed and capped at %.1f km/h",
      highest_kmh, vmax_kmh);
}

nlohmann::json section_report_json(const dp::SectionSolution& solution, const physics::Train& train,
                                   const std::string& cap_note, const nlohmann::json& provenance) {
  nlohmann::json report = section_solution_json(solution);
  report["notes"] = notes_json(cap_note);
  report["auxiliary_energy_kJ"] = auxiliary_energy_kJ(train, solution.summary.running_time_s);
  report["provenance"] = provenance;
  return report;
}

nlohmann::json journey_report_json(const dp::JourneySolution& sol, const JourneyLabels& labels,
                                   const physics::Train& train, const std::string& cap_note,
                                   const dp::MinRegimeOptions& min_regime,
                                   const nlohmann::json& provenance) {
  nlohmann::json report = journey_json(sol, labels);
  report["provenance"] = provenance;
  report["notes"] = notes_json(cap_note);
  report["auxiliary_energy_kJ"] =
      auxiliary_energy_kJ(train, report.at("trip_time_s").get<double>());
  if (min_regime.active()) {
    report["min_regime"] = {{"min_length_m", min_regime.min_length_m},
                            {"min_duration_s", min_regime.min_duration_s},
                            {"merged_phases", sol.merged_regimes},
                            {"unmerged_energy_kJ", units::J_to_kJ(sol.unmerged_cost_J)},
                            {"cost_kJ", units::J_to_kJ(sol.merged_cost_J - sol.unmerged_cost_J)}};
  }
  return report;
}

std::vector<std::string> timing_journey_stops(const dp::TimingJourneySolution& sol) {
  std::vector<std::string> stops;
  for (const auto& part : sol.parts) stops.push_back(dp::format_text("%.1f m", part.start_m));
  stops.push_back(dp::format_text("%.1f m", sol.parts.back().end_m));
  return stops;
}

nlohmann::json timing_journey_report_json(const dp::TimingJourneySolution& sol,
                                          const std::string& journey_id, double ds_m, double dv_kmh,
                                          const nlohmann::json& provenance) {
  const JourneyLabels labels{timing_journey_stops(sol), "timing points", ds_m, dv_kmh, 0};
  nlohmann::json report = journey_json(sol.journey, labels);
  report["journey"] = journey_id;
  report["windows_met"] = sol.windows_met;
  report["windows"] = windows_json(sol);
  report["trip_time_s"] = sol.summary.trip_time_s;
  report["departure_s"] = sol.parts.front().departure_s;
  nlohmann::json parts = nlohmann::json::array();
  for (const auto& part : sol.parts) {
    nlohmann::json lambdas = nlohmann::json::array();
    for (double l : part.stretch_lambda_J_per_s) lambdas.push_back(l / 1000.0);
    parts.push_back({{"from_m", part.start_m},
                     {"to_m", part.end_m},
                     {"departure_s", part.departure_s},
                     {"arrival_target_s", part.arrival_target_s},
                     {"stretch_lambda_kJ_per_s", lambdas},
                     {"price_evaluations", part.evaluations}});
  }
  report["parts"] = parts;
  report["provenance"] = provenance;
  report["notes"] = nlohmann::json::array();
  return report;
}

nlohmann::json min_time_report_json(const physics::Route& route,
                                    const physics::SimulationResult& sim,
                                    const physics::Train& train, const nlohmann::json& provenance) {
  nlohmann::json j = run_json(sim);
  j["from"] = route.from_name();
  j["to"] = route.to_name();
  j["distance_m"] = route.length_m();
  j["min_running_time_s"] = sim.running_time_s;
  j["auxiliary_energy_kJ"] = auxiliary_energy_kJ(train, sim.running_time_s);
  j["provenance"] = provenance;
  return j;
}

nlohmann::json frontier_report_json(const std::vector<LabelledFrontier>& frontiers, bool all,
                                    double ds_m, double dv_kmh, const nlohmann::json& provenance) {
  nlohmann::json j = nlohmann::json::array();
  for (const auto& lf : frontiers) j.push_back(frontier_json(lf));
  nlohmann::json doc = all ? nlohmann::json{{"frontiers", j}} : j[0];
  doc["grid"] = {{"ds_m", ds_m}, {"dv_kmh", dv_kmh}};
  doc["provenance"] = provenance;
  return doc;
}

}  // namespace ecorail::output
