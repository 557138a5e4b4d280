#include "recovery/delay_report.hpp"

#include <cmath>
#include <cstdio>

#include "data/csv_reader.hpp"

namespace ecorail::recovery {

namespace {

nlohmann::json number_or_null(double v) {
  return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
}

}  // namespace

void write_delay_sections_csv(std::ostream& out, const DelayRecoveryResult& r) {
  out << "from,to,min_time_s,planned_time_s,new_time_s,rule_time_s,plan_energy_kJ,"
         "new_energy_kJ,rule_energy_kJ,marginal_kJ_per_s,flat_out,planned_dwell_s,new_dwell_s,"
         "new_departure_s,planned_arrival_s,new_arrival_s\n";
  char buf[512];
  for (const auto& s : r.sections) {
    std::snprintf(
        buf, sizeof buf,
        "%s,%s,%.3f,%.3f,%.3f,%.3f,%.1f,%.1f,%.1f,%s,%d,%.3f,%.3f,%.3f,%.3f,%.3f\n", s.from.c_str(),
        s.to.c_str(), s.min_time_s, s.planned_time_s, s.new_time_s, s.rule_time_s, s.plan_energy_kJ,
        s.new_energy_kJ, s.rule_energy_kJ,
        std::isfinite(s.marginal_kJ_per_s) ? data::format_number(s.marginal_kJ_per_s).c_str() : "",
        s.flat_out ? 1 : 0, s.planned_dwell_s, s.new_dwell_s, s.new_departure_s,
        s.planned_arrival_s, s.new_arrival_s);
    out << buf;
  }
}

nlohmann::json delay_report_json(const DelayRecoveryResult& r, const Plan& plan, int train_number,
                                 const std::string& plan_name) {
  const auto& sm = r.summary;
  nlohmann::json sections = nlohmann::json::array();
  for (const auto& s : r.sections)
    sections.push_back({{"from", s.from},
                        {"to", s.to},
                        {"min_time_s", s.min_time_s},
                        {"planned_time_s", s.planned_time_s},
                        {"new_time_s", s.new_time_s},
                        {"rule_time_s", s.rule_time_s},
                        {"plan_energy_kJ", s.plan_energy_kJ},
                        {"new_energy_kJ", s.new_energy_kJ},
                        {"rule_energy_kJ", s.rule_energy_kJ},
                        {"marginal_kJ_per_s", number_or_null(s.marginal_kJ_per_s)},
                        {"flat_out", s.flat_out},
                        {"planned_dwell_s", s.planned_dwell_s},
                        {"new_dwell_s", s.new_dwell_s},
                        {"new_departure_s", s.new_departure_s},
                        {"planned_arrival_s", s.planned_arrival_s},
                        {"new_arrival_s", s.new_arrival_s}});
  nlohmann::json trains = nlohmann::json::array();
  for (const auto& t : r.trains)
    trains.push_back(
        {{"train", t.train + 1},
         {"back_on_time_at",
          t.back_on_time_at.empty() ? nlohmann::json(nullptr) : nlohmann::json(t.back_on_time_at)},
         {"never_late", t.never_late},
         {"max_lateness_s", t.max_lateness_s},
         {"final_lateness_s", t.final_lateness_s},
         {"lateness_s", t.lateness_s}});
  nlohmann::json followers = nlohmann::json::array();
  for (const auto& f : r.followers)
    followers.push_back({{"train", f.train + 1},
                         {"behind_train", f.behind + 1},
                         {"affected", f.affected},
                         {"min_speed_margin_kmh", number_or_null(f.min_speed_margin_kmh)},
                         {"min_distance_margin_m", number_or_null(f.min_distance_margin_m)},
                         {"min_gap_m", number_or_null(f.min_gap_m)},
                         {"planned_run_margin_kmh", number_or_null(f.planned_run_margin_kmh)},
                         {"plan_margin_kmh", number_or_null(f.plan_margin_kmh)},
                         {"on_the_line_together", std::isfinite(f.min_speed_margin_kmh)},
                         {"station_wait_s", f.station_wait_s},
                         {"headway_s", f.headway_s},
                         {"traction_kJ", f.traction_kJ},
                         {"plan_traction_kJ", f.plan_traction_kJ},
                         {"lateness_sum_s", f.lateness_sum_s}});
  nlohmann::json j = {
      {"train", train_number},
      {"station", sm.station},
      {"delay_s", sm.delay_s},
      {"plan", plan_name},
      {"stations", plan.stations},
      {"recovered", sm.recovered},
      {"back_on_time_at",
       sm.recovered ? nlohmann::json(sm.back_on_time_at) : nlohmann::json(nullptr)},
      {"final_lateness_s", sm.final_lateness_s},
      {"sections_used", sm.sections},
      {"recovery_energy_kJ", sm.recovery_energy_kJ},
      {"plan_energy_kJ", sm.plan_energy_kJ},
      {"rule_energy_kJ", sm.rule_energy_kJ},
      {"rule_extra_energy_kJ", sm.rule_energy_kJ - sm.recovery_energy_kJ},
      {"recovery_mode", sm.recovery_mode},
      {"total_lateness_s", sm.total_lateness_s},
      {"energy_first_energy_kJ", number_or_null(sm.energy_first_energy_kJ)},
      {"energy_first_total_lateness_s", number_or_null(sm.energy_first_total_lateness_s)},
      {"sections", sections},
      {"trains", trains},
      {"followers", followers},
      {"followers_affected", sm.followers_affected},
      {"cascade",
       {{"held_up_trains", sm.cascade_trains},
        {"ends", sm.cascade_ends},
        {"plan_absorbs", sm.plan_absorbs},
        {"final_lateness_s", sm.cascade_final_lateness_s}}},
      {"min_follower_margin_kmh", number_or_null(sm.min_follower_margin_kmh)},
      {"termination", std::string(dp::termination_name(sm.termination))},
      {"warnings", sm.warnings},
      {"brief_report", sm.BriefReport()},
      {"wall_s", sm.wall_s}};
  if (r.allocation.sections > 0)
    j["allocation"] = {{"method",
                        "bisection on the common marginal energy per second over the "
                        "sections' frontier curves (exact for convex frontiers)"},
                       {"termination", std::string(dp::termination_name(r.allocation.termination))},
                       {"lambda_kJ_per_s", r.allocation.lambda_J_per_s / 1e3},
                       {"sections", r.allocation.sections},
                       {"at_minimum_time", r.allocation.at_lower},
                       {"at_upper_bound", r.allocation.at_upper},
                       {"iterations", r.allocation.iterations},
                       {"energy_by_frontiers_kJ", r.allocation.energy_J / 1e3},
                       {"brief_report", r.allocation.BriefReport()}};
  if (sm.recovery_mode == "lateness-first") j["lateness_first"] = r.allocation.message;
  return j;
}

}  // namespace ecorail::recovery
