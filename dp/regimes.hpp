// Regime spans: the driving regimes of a re-simulated run (full traction, partial traction or
// cruise, coast, partial brake, full brake), each with where and when it starts and ends and
// the speeds there. Built from the trace, so they describe what the train did, not what the
// optimiser intended. A span of partial force at a steady speed is a speed hold (cruising, or
// holding a limit): what a driver is told as "hold X km/h".
//
// A minimum regime length or duration (MinRegimeOptions) makes the advice one a driver can
// follow: the solved run's control phases shorter than the minimum are merged into the phase
// before them, the run is re-simulated and trimmed back to its running time (the switch-point
// trim of dp/time_target.hpp), and the energy that costs is measured against the unmerged run.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "dp/section_engine.hpp"
#include "physics/simulator.hpp"

namespace ecorail::dp {

struct RegimeSpan {
  physics::Regime regime = physics::Regime::Coast;
  double start_m = 0.0, end_m = 0.0;
  double start_speed_ms = 0.0, end_speed_ms = 0.0;
  double start_time_s = 0.0, end_time_s = 0.0;
  // Partial traction or partial braking with the speed steady (within kHoldBand_ms over the
  // span): a speed hold.
  bool speed_hold = false;
};
inline constexpr double kHoldBand_ms = 0.25 / 3.6;

// Consecutive trace steps with the same regime form a span; spans shorter than min_length_m
// (integration slivers at switch points) are merged into the span before them.
std::vector<RegimeSpan> regime_spans(const BigVector<physics::TracePoint>& trace,
                                     double min_length_m = 0.5);
// "speed_hold" for a speed hold, else the regime's name (physics::regime_name).
std::string_view span_name(const RegimeSpan& span);

struct MinRegimeOptions {
  double min_length_m = 0.0;    // 0: no minimum length
  double min_duration_s = 0.0;  // 0: no minimum duration
  bool active() const { return min_length_m > 0.0 || min_duration_s > 0.0; }
  // Checks every field; on failure writes one sentence naming the field into *error.
  bool IsValid(std::string* error) const;
};

struct MinRegimeResult {
  LambdaRun run;             // merged, re-simulated and trimmed (the input run when inactive)
  int merged_entries = 0;    // control phases merged away
  int rounds = 0;            // merge and trim rounds
  int trim_simulations = 0;  // re-simulations of the trims
  double cost_before_J = 0.0, cost_after_J = 0.0;  // energy by the engine's objective
  int short_entries_left = 0;                      // phases still below the minimum (0 if met)
  bool met = true;  // the merged run arrives and runs within the time tolerance of the target
};

// Merges the short phases of run (a run of engine, e.g. a solve's result) and trims it back to
// target_time_s. Up to three rounds of merge and trim, since a trim can shorten a phase again.
MinRegimeResult enforce_min_regime(const SectionEngine& engine, const LambdaRun& run,
                                   double target_time_s, const MinRegimeOptions& options);

}  // namespace ecorail::dp
