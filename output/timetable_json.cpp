#include "output/timetable_json.hpp"

#include <cmath>
#include <string>

#include "output/fleet_outputs.hpp"

namespace ecorail::output {

namespace {

// What both reports carry besides the energy: the pattern, per-train patterns, the stations and
// the network's account.
void add_study(nlohmann::json& energy, const fleet::TimetableStudy& study,
               const energy::FleetEvaluation& ev) {
  const fleet::FleetPattern& pattern = study.pattern().pattern;
  energy["pattern"] = {{"dwells_s", pattern.dwells_s},
                       {"running_times_s", pattern.running_times_s},
                       {"trip_time_s", pattern.trip_time_s()}};
  if (!study.per_train_patterns().empty()) {
    nlohmann::json patterns = nlohmann::json::array();
    for (std::size_t k = 0; k < study.per_train_patterns().size(); ++k) {
      const fleet::FleetPattern& p = study.per_train_patterns()[k];
      patterns.push_back({{"train", k + 1},
                          {"dwells_s", p.dwells_s},
                          {"running_times_s", p.running_times_s},
                          {"trip_time_s", p.trip_time_s()}});
    }
    energy["patterns_per_train"] = patterns;
  }
  energy["stations"] = study.stops();
  if (ev.network) add_network_json(energy, *ev.network);
}

nlohmann::json pattern_search_json(const fleet::PatternSearchResult& r) {
  const auto& before = r.headways_only.total;
  const auto& after = r.timetable.evaluation.total;
  nlohmann::json j = {{"moves_accepted", r.moves_accepted},
                      {"patterns_evaluated", r.patterns_evaluated},
                      {"headways_only_substation_energy_kJ", before.substation_J() / 1e3},
                      {"headways_only_traction_energy_kJ", before.traction_J / 1e3},
                      {"headways_only_used_regen_kJ", r.headways_only.used_regen_J() / 1e3},
                      {"retiming_saving_kJ", (before.substation_J() - after.substation_J()) / 1e3},
                      {"retiming_traction_cost_kJ", (after.traction_J - before.traction_J) / 1e3}};
  if (!r.per_train.empty()) {
    const auto& common = r.common_pattern.total;
    j["per_train_patterns"] = true;
    j["per_train_moves_accepted"] = r.per_train_moves_accepted;
    j["per_train_candidates_priced"] = r.per_train_candidates;
    j["common_pattern_substation_energy_kJ"] = common.substation_J() / 1e3;
    j["common_pattern_traction_energy_kJ"] = common.traction_J / 1e3;
    j["per_train_saving_kJ"] = (common.substation_J() - after.substation_J()) / 1e3;
    j["per_train_traction_cost_kJ"] = (after.traction_J - common.traction_J) / 1e3;
    j["per_train_stop"] = r.time_limit_reached   ? "time limit"
                          : r.move_limit_reached ? "move limit"
                                                 : "local optimum";
  }
  return j;
}

}  // namespace

nlohmann::json timetable_evaluation_json(const fleet::TimetableStudy& study,
                                         const fleet::StudyEvaluation& e) {
  nlohmann::json energy = fleet_energy_json(e.evaluation, study.problem());
  if (e.substation_without_reuse_J && e.evaluation.network) {
    const double off = *e.substation_without_reuse_J;
    energy["substation_energy_without_regen_kJ"] = off / 1e3;
    energy["regen_saving_kJ"] = (off - e.evaluation.network->substation_J) / 1e3;
  }
  add_study(energy, study, e.evaluation);
  return energy;
}

nlohmann::json timetable_optimisation_json(const fleet::TimetableStudy& study,
                                           const fleet::StudyOptimisation& o, std::uint64_t seed) {
  const fleet::HeadwayOptimiserResult& result = o.result;
  nlohmann::json energy = fleet_energy_json(result.evaluation, study.problem());
  const auto& sm = result.summary;
  if (std::isfinite(sm.bound_substation_J)) {
    // Network model: a lower bound on substation + curtailed traction energy.
    energy["bound_substation_kJ"] = sm.bound_substation_J / 1e3;
    energy["gap_fraction_of_substation"] = sm.gap_fraction;
  } else if (std::isfinite(sm.bound_used_regen_J)) {
    energy["bound_used_regen_kJ"] = sm.bound_used_regen_J / 1e3;
    energy["gap_fraction_of_substation"] = sm.gap_fraction;
    if (sm.pair_sum_J > 0.0) energy["pair_sum_of_result_kJ"] = sm.pair_sum_J / 1e3;
  }
  energy["summary"] = {{"termination", std::string(fleet::termination_name(sm.termination))},
                       {"method", sm.method},
                       {"exact", sm.exact},
                       {"seed", seed},
                       {"moves", sm.moves},
                       {"wall_s", sm.wall_s},
                       {"gap_fraction_of_substation", sm.gap_fraction},
                       {"brief_report", sm.BriefReport()}};
  if (!sm.message.empty()) energy["summary"]["message"] = sm.message;
  if (!sm.exact_part.empty())
    energy["summary"]["exact_part"] = {{"timetables", "every timetable with " + sm.exact_part},
                                       {"best_used_regen_kJ", sm.exact_part_used_J / 1e3}};
  if (std::isfinite(sm.given_start_used_J))
    energy["summary"]["given_start_used_regen_kJ"] = sm.given_start_used_J / 1e3;
  if (o.pattern_search) energy["pattern_search"] = pattern_search_json(*o.pattern_search);
  add_study(energy, study, result.evaluation);
  return energy;
}

}  // namespace ecorail::output
