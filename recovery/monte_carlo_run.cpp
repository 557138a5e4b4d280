#include "recovery/monte_carlo_run.hpp"

#include <chrono>
#include <cmath>

namespace ecorail::recovery {

namespace {

nlohmann::json estimate_brief(const Estimate& e) {
  return {{"mean", e.mean}, {"ci95", e.ci95}};
}

bool finite(const Estimate& e) {
  return std::isfinite(e.mean) && std::isfinite(e.ci95);
}

// CONVERGENCE when the run holds every day it was asked for and its statistics are numbers.
dp::Termination termination_of(const MonteCarloStatistics& s, std::uint64_t days_wanted) {
  const bool complete = s.days >= 0 && static_cast<std::uint64_t>(s.days) == days_wanted;
  const bool numbers = finite(s.punctuality) && finite(s.mean_lateness_s) &&
                       finite(s.p95_lateness_s) && finite(s.traction_kJ) && finite(s.substation_kJ);
  return complete && numbers ? dp::Termination::CONVERGENCE : dp::Termination::FAILURE;
}

}  // namespace

std::optional<RecoveryPolicy> recovery_policy_from_name(const std::string& name) {
  for (RecoveryPolicy p :
       {RecoveryPolicy::Exact, RecoveryPolicy::ExactPunctual, RecoveryPolicy::Rule})
    if (name == recovery_policy_name(p)) return p;
  return std::nullopt;
}

std::optional<FollowerModel> follower_model_from_name(const std::string& name) {
  for (FollowerModel m : {FollowerModel::Driven, FollowerModel::Shortcut})
    if (name == follower_model_name(m)) return m;
  return std::nullopt;
}

nlohmann::json monte_carlo_config(const MonteCarlo& mc, const MonteCarloRunInfo& info) {
  const MonteCarloOptions& o = mc.options();
  return {{"plan", info.plan_name},
          {"trains", mc.plan().trains.size()},
          {"days", info.days_total},
          {"seed", o.seed},
          {"recovery", recovery_policy_name(o.recovery)},
          {"followers", follower_model_name(o.followers)},
          {"p_none", o.delays.p_none},
          {"p_small", o.delays.p_small},
          {"small_max_s", o.delays.small_max_s},
          {"tail", o.delays.tail_text()},
          {"early_s", o.early_s},
          {"run_early_s", o.run_early_s},
          {"min_dwell_s", o.min_dwell_s},
          {"takeover_s", o.takeover_s},
          {"punctual_s", o.punctual_s},
          {"on_time_tolerance_s", o.on_time_tolerance_s},
          {"separation_s", mc.separation_s()},
          {"knot_step_s", o.knot_step_s},
          {"bin_step_s", o.bin_step_s},
          {"frontier_span_s", info.frontier_span_s},
          {"ds_m", info.ds_m},
          {"dv_kmh", info.dv_kmh},
          {"line_checksum", std::to_string(info.line_checksum)},
          {"train_checksum", std::to_string(info.train_checksum)}};
}

MonteCarloDays simulate_days(const MonteCarlo& mc, const SectionRuns& runs, std::uint64_t first,
                             std::uint64_t last, int threads, const MonteCarloRunInfo& info,
                             const std::function<void(int, int)>& progress,
                             std::chrono::steady_clock::time_point wall_start) {
  const DayRecord plan_day = mc.plan_day();
  std::vector<DayRecord> days = mc.run_days(first, last, threads, progress);
  MonteCarloDays out;
  MonteCarloRun& run = out.run;
  run.stations = mc.plan().stations;
  run.histogram = pooled_histogram(days);
  run.days = std::move(days);
  run.plan_energy = {{"traction_kJ", plan_day.traction_kJ},
                     {"substation_kJ", plan_day.substation_kJ},
                     {"used_regen_kJ", plan_day.used_regen_kJ},
                     {"regen_kJ", plan_day.regen_kJ}};
  run.config = monte_carlo_config(mc, info);
  MonteCarloSummary& sm = out.summary;
  sm.first_day = first;
  sm.last_day = last;
  sm.threads = threads;
  sm.followers = follower_model_name(mc.options().followers);
  sm.separation_s = mc.separation_s();
  sm.section_runs = runs.piece_count();
  sm.statistics = summarise(run.days, run.histogram);
  sm.plan_traction_kJ = plan_day.traction_kJ;
  sm.plan_substation_kJ = plan_day.substation_kJ;
  sm.termination = termination_of(sm.statistics, last > first ? last - first : 0);
  sm.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  return out;
}

MonteCarloSummary run_summary(const MonteCarloRun& run) {
  MonteCarloSummary sm;
  sm.first_day = 0;
  sm.last_day = run.days.size();
  sm.statistics = summarise(run.days, run.histogram);
  sm.plan_substation_kJ = run.plan_energy.value("substation_kJ", 0.0);
  sm.plan_traction_kJ = run.plan_energy.value("traction_kJ", 0.0);
  sm.termination = termination_of(sm.statistics, run.days.size());
  // A run written before the followers were driven was the shortcut.
  if (run.config.is_object()) {
    sm.followers = run.config.value("followers", std::string("shortcut"));
    sm.separation_s = run.config.value("separation_s", 0.0);
  }
  return sm;
}

nlohmann::json plan_adjustment_json(const PlanAdjustmentResult& r, const std::string& plan_name,
                                    std::int64_t seed, std::int64_t search_days) {
  nlohmann::json cands = nlohmann::json::array();
  for (const PlanCandidate& c : r.candidates) {
    const MonteCarloStatistics& s = c.statistics;
    cands.push_back({{"theta", c.theta},
                     {"extra_dwell_s", c.extra_dwell_s},
                     {"run_early_s", c.run_early_s},
                     {"running_times_s", c.running_times_s},
                     {"dwells_s", c.dwells_s},
                     {"meets_target", c.meets_target},
                     {"plan_traction_kJ", c.plan_traction_kJ},
                     {"plan_substation_kJ", c.plan_substation_kJ},
                     {"punctuality", estimate_brief(s.punctuality)},
                     {"mean_lateness_s", estimate_brief(s.mean_lateness_s)},
                     {"p95_lateness_s", estimate_brief(s.p95_lateness_s)},
                     {"recovery_time_s", estimate_brief(s.recovery_time_s)},
                     {"traction_kJ", estimate_brief(s.traction_kJ)},
                     {"substation_kJ", estimate_brief(s.substation_kJ)}});
  }
  return {{"plan", plan_name},
          {"seed", seed},
          {"search_days", search_days},
          {"target_punctuality", r.summary.target_punctuality},
          {"target_met", r.summary.target_met},
          {"chosen", r.summary.chosen},
          {"chosen_run_early_s", r.chosen().run_early_s},
          {"candidates", cands},
          {"warnings", r.summary.warnings},
          {"brief_report", r.summary.BriefReport()}};
}

}  // namespace ecorail::recovery
