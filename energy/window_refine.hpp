// An exact search near a headway sequence for the power-flow model with one supply section: the
// best sequence whose every headway lies within max_step_s of the given one's, in the core
// (energy/window_terms.hpp: at least L / 4, so at most four trains share the line) and with the
// same sum (the span), found by a DP over the sequence whose state is the last two changes and
// the change of the sum so far (kept within max_shift_s). On the core the used energy is exactly
// a sum of window terms of three consecutive headways (energy/window_terms.hpp), computed on the
// model's own grid, so the DP's value is the model's used energy, not a relaxation; the search
// repeats from its result until a pass gains nothing. It moves many headways at once, which the
// heuristic's one-train moves cannot: from the annealed and polished reference timetable one
// pass gains where the polish had stopped (docs/fleet.md). A headway outside the core, or more
// than one supply section, makes it not applicable (the input is returned).
#pragma once

#include <string>
#include <vector>

#include "energy/model_options.hpp"
#include "energy/power_flow_profile.hpp"

namespace ecorail::energy {

struct WindowRefineOptions {
  int max_step_s = 3;    // a headway moves by at most this much in a pass (s)
  int max_shift_s = 30;  // the partial sums move by at most this much in a pass (s)
  int max_passes = 20;
  double time_limit_s = 0.0;  // checked between passes; 0: none
  int threads = 0;            // 0: OpenMP's default (the window terms are computed in parallel)
  bool IsValid(std::string* error) const;
};

struct WindowRefineSummary {
  bool applicable = false;
  std::string why_not;          // when not applicable
  std::vector<int> headways_s;  // the result (the input when not applicable)
  double start_used_J = 0.0;    // used regenerated energy of the input, on the model's grid
  double used_J = 0.0;          // of the result (never less)
  int passes = 0;
  long window_terms = 0;  // distinct window terms computed
  bool time_limit_reached = false;
  double wall_s = 0.0;
};

WindowRefineSummary window_refine(const PowerProfile& profile, const FleetLimits& limits,
                                  const std::vector<int>& headways_s,
                                  const WindowRefineOptions& options = {});

}  // namespace ecorail::energy
