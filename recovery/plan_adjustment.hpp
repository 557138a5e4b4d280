// Plan adjustment for random delays (question 3.2, part 2): choose where a plan keeps its
// running-time margin, and its dwells, to minimise the expected substation energy of a service
// day subject to a punctuality target. The family searched is small and stated: every train
// keeps its departure from the first station and its trip time (so the timetable's ends and
// headways are the 2.2 plan's); the dwells are the plan's plus extra_dwell_s at every
// intermediate stop (at most max_dwell_s); the running time left is split as
// (1 - theta) x the energy-optimal split (one time price) + theta x equal margins above the
// flat-out times (theta = 0: the energy-optimal plan; theta = 1: every section the same
// margin, the most even protection against a delay on any section); and the plan may be run
// ahead of the timetable by run_early_s within the early allowance (the same running times and
// so the same plan energy; a buffer against delays). Every candidate is run on
// the same days with the same seed (common random numbers) and the exact recovery; the chosen
// one has the least mean substation energy among those whose mean punctuality reaches the
// target (or, when none does, the most punctual, flagged).
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "dp/termination.hpp"
#include "recovery/monte_carlo.hpp"

namespace ecorail::recovery {

struct PlanAdjustmentOptions {
  std::vector<double> thetas = {0.0, 0.25, 0.5, 0.75, 1.0};
  std::vector<double> extra_dwells_s = {0.0, 3.0};
  // Operating offsets: the plan run this much ahead of the timetable (MonteCarloOptions::
  // run_early_s), within the early allowance.
  std::vector<double> run_early_s = {0.0};
  double max_dwell_s = 45.0;
  std::uint64_t search_days = 200;
  double target_punctuality = 0.97;
  int threads = 0;
  // Checks every field; on failure writes one sentence naming the field into *error.
  bool IsValid(std::string* error) const;
};

struct PlanCandidate {
  double theta = 0.0, extra_dwell_s = 0.0, run_early_s = 0.0;
  std::vector<double> running_times_s, dwells_s;
  Plan plan;
  MonteCarloStatistics statistics;
  double plan_traction_kJ = 0.0, plan_substation_kJ = 0.0;
  bool meets_target = false;
};

struct PlanAdjustmentSummary {
  dp::Termination termination = dp::Termination::FAILURE;
  int candidates = 0;
  std::size_t chosen = 0;
  bool target_met = false;
  double target_punctuality = 0.0;
  std::vector<std::string> warnings;
  std::string BriefReport() const;
  std::string FullReport() const;
  bool IsSolutionUsable() const { return dp::is_usable(termination); }
};

struct PlanAdjustmentResult {
  std::vector<PlanCandidate> candidates;
  PlanAdjustmentSummary summary;
  const PlanCandidate& chosen() const { return candidates.at(summary.chosen); }
};

// The plan's one pattern (running times per section, dwells per intermediate stop); throws
// std::invalid_argument when its trains do not all run one pattern (within 1 ms).
void plan_pattern(const Plan& plan, std::vector<double>* running_times_s,
                  std::vector<double>* dwells_s);

// progress (may be empty): (candidate done, candidates).
PlanAdjustmentResult adjust_plan(const dp::SectionLibrary& library, const Plan& base,
                                 const MonteCarloOptions& simulation, SectionRuns& runs,
                                 const PlanAdjustmentOptions& options,
                                 const std::function<void(int, int)>& progress = {});

}  // namespace ecorail::recovery
