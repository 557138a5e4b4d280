// Journeys: one train over several consecutive sections with dwells between them and one total
// running time (dwells excluded, as the published problem counts it). With the optimal split,
// a single time price lambda applies to every section, so at the optimum each section's
// marginal energy per second is the same; lambda is searched on the total re-simulated time and
// the last hundredths are closed by trimming one section (first-order neutral, as in the
// single-section search). The proportional split gives each section a share of the time in
// proportion to its length and solves each on its own, for comparison with published methods.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "dp/regimes.hpp"
#include "dp/section_engine.hpp"
#include "dp/time_target.hpp"

namespace ecorail::dp {

enum class Split { Optimal, Proportional };

struct JourneyOptions {
  EngineOptions engine;
  TimeSearchOptions search;
  Split split = Split::Optimal;
  // Measure each section's marginal energy per second by re-solving it at +-0.5 s.
  bool measure_marginals = true;
  double marginal_step_s = 0.5;
};

struct JourneySection {
  LambdaRun run;
  std::vector<RegimeSpan> regimes;
  double dwell_after_s = 0.0;     // at the section's arrival stop (0 for the last)
  double marginal_J_per_s = 0.0;  // -(dE/dT) measured by re-solving; NaN if not measured
  double min_time_s = 0.0;
};

struct JourneySolution {
  std::vector<JourneySection> sections;
  double lambda_J_per_s = 0.0;  // common price (optimal split); NaN for proportional
  double target_time_s = 0.0;
  double running_time_s = 0.0;  // sum of section times
  double traction_work_J = 0.0;
  double brake_work_J = 0.0;
  double regen_J = 0.0;
  double net_J = 0.0;
  int lambda_evaluations = 0;
  bool converged = false;
  double build_wall_s = 0.0;
  double search_wall_s = 0.0;
  double total_wall_s = 0.0;
  std::vector<std::string> warnings;
};

// Solves a journey over `routes` (consecutive sections) with `dwells_s[i]` after section i.
JourneySolution solve_journey(const physics::Train& train,
                              const std::vector<physics::Route>& routes,
                              const std::vector<double>& dwells_s, double total_time_s,
                              const JourneyOptions& options);

}  // namespace ecorail::dp
