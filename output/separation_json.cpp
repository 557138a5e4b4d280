#include "output/separation_json.hpp"

#include <cmath>

#include "service/pattern_service.hpp"

namespace ecorail::output {

namespace {

nlohmann::json stretch_json(std::size_t train, const service::CapStretch& c) {
  return {{"train", train + 1}, {"from_s", c.from_s}, {"to_s", c.to_s},
          {"from_m", c.from_m}, {"to_m", c.to_m},     {"worst_margin_kmh", c.worst_margin_kmh}};
}

}  // namespace

nlohmann::json separation_json(const service::ServiceResult& r, const service::ServiceOptions& o) {
  const service::ServiceSummary& sm = r.summary;
  nlohmann::json binding = nlohmann::json::array();
  for (std::size_t k = 0; k < r.planned_binding.size(); ++k)
    for (const auto& c : r.planned_binding[k]) binding.push_back(stretch_json(k, c));
  nlohmann::json events = nlohmann::json::array();
  for (const auto& e : r.events) {
    events.push_back({{"train", e.train + 1},
                      {"section", e.section + 1},
                      {"planned_energy_kJ", e.planned_cost_J / 1e3},
                      {"supervised_energy_kJ", e.supervised_cost_J / 1e3},
                      {"supervised_late_s", e.supervised_late_s},
                      {"reoptimised_energy_kJ", std::isfinite(e.reoptimised_cost_J)
                                                    ? nlohmann::json(e.reoptimised_cost_J / 1e3)
                                                    : nlohmann::json()},
                      {"reoptimised_late_s", e.reoptimised_late_s},
                      {"reoptimised_wait_s", e.reoptimised_wait_s},
                      {"report", e.report},
                      {"station_wait_s", e.station_wait_s},
                      {"driven", e.driven},
                      {"late_s", e.late_s}});
  }
  double traction_J = 0.0;
  for (const auto& t : r.trips) traction_J += t.ledger().traction_work_J;
  return {{"braking_m_s2", r.braking_m_s2},
          {"train_length_m", o.separation.train_length_m},
          {"safety_margin_m", o.separation.safety_margin_m},
          {"follower", service::follower_mode_name(o.mode)},
          {"min_speed_margin_kmh", sm.min_speed_margin_kmh},
          {"min_distance_margin_m", sm.min_distance_margin_m},
          {"min_gap_m", sm.min_gap_m},
          {"min_margin_train", sm.min_margin_train + 1},
          {"min_margin_at_s", sm.min_margin_at_s},
          {"min_margin_at_m", sm.min_margin_at_m},
          {"cap_binds_at_plan", !binding.empty()},
          {"cap_exceeded", sm.cap_exceeded},
          {"trains_resimulated", sm.trains_resimulated},
          {"max_late_s", sm.max_late_s},
          {"service_traction_work_kJ", traction_J / 1e3},
          {"planned_binding", binding},
          {"events", events},
          {"brief_report", sm.BriefReport()}};
}

}  // namespace ecorail::output
