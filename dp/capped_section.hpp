// Energy-optimal run of one section under a moving speed cap (question 2.2: a follower behind a
// train ahead, v <= cap(t, s), e.g. min(v_line, sqrt(2 L b))). The cap depends on the clock, so
// the optimal run depends on when the train is where: the DP's state carries time. It is a
// forward DP over position stages (stage_m apart) whose labels are exact states (speed, clock
// time, energy so far) reached by integrating each control (full traction, hold, coast, full
// braking) over the stage with the same Motion kernel as the section engine, the cap supervised
// at every substep as the simulator supervises it; per stage one label is kept per (speed, time)
// bucket, the one of least energy. Waiting at the departure stop (0 to max_wait_s) is part of
// the search, as the first labels. A label that could not arrive on time even at the line's
// top speed is dropped (when no label arrives on time the DP runs again without that rule and
// the fastest run is taken). At the stop, the label of least energy that arrives within
// the time budget is taken (when none does, the least energy arriving within a second of the
// fastest: it arrives late, reported as
// NO_CONVERGENCE); its controls become a control program that is re-simulated at the fine step
// under the same cap, and the switch into the final coast is moved (bisection on the measured
// time) so that the run arrives when planned. Then the switch points are polished on the
// simulator itself (each tried on a grid around where it is, every trial fitted to the time,
// until a sweep changes nothing): the DP's stages put switches only at stage ends and its
// coarse integration misprices them by a few per cent. Every figure reported is the
// re-simulation's.
#pragma once

#include <string>

#include "dp/section_engine.hpp"
#include "dp/termination.hpp"
#include "physics/simulator.hpp"

namespace ecorail::dp {

struct CappedSectionOptions {
  double stage_m = 10.0;         // DP stage length
  double speed_bucket_ms = 0.2;  // one label per bucket of speed ...
  double time_bucket_s = 1.0;    // ... and of clock time
  double substep_m = 5.0;        // Heun substeps inside a stage
  double max_wait_s = 60.0;      // longest wait at the departure stop
  double wait_step_s = 2.0;
  double resim_step_m = 0.05;      // RK4 re-simulation
  double time_tolerance_s = 0.1;   // arrival within this of the budget counts as on time
  int polish_sweeps = 3;           // switch-point polish after the DP (0: none)
  double polish_window_m = 100.0;  // each switch tried within +-window ...
  double polish_step_m = 10.0;     // ... on this grid
  bool IsValid(std::string* error) const;
};

struct CappedSectionSummary {
  Termination termination = Termination::FAILURE;
  long labels = 0;  // labels kept over all stages
  int stages = 0;
  double dp_cost_J = 0.0;      // the DP's own estimate
  double cost_J = 0.0;         // re-simulated, by the engine's objective
  double time_budget_s = 0.0;  // from the planned departure to the planned arrival
  double total_time_s = 0.0;   // wait plus running time, re-simulated
  double wait_s = 0.0;
  double max_cap_overspeed_ms = 0.0;  // re-simulated, <= 0 when the cap is respected
  int trim_iterations = 0;
  long polish_trials = 0;
  std::string message;
  bool IsSolutionUsable() const { return is_usable(termination); }
  std::string BriefReport() const;
  std::string FullReport() const;
};

struct CappedSectionResult {
  physics::ControlProgram program;  // from the departure, after the wait
  double wait_s = 0.0;
  physics::SimulationResult sim;  // re-simulated under the cap, clock from start + wait
  CappedSectionSummary summary;
};

// start_clock_s: the planned departure from the section's first stop (the cap's clock);
// time_budget_s: planned arrival minus that departure. hint (optional, e.g. the planned
// control) is fitted to the time too and polished instead of the DP's run when it does better.
CappedSectionResult solve_capped_section(const SectionEngine& engine, const physics::SpeedCap& cap,
                                         double start_clock_s, double time_budget_s,
                                         const CappedSectionOptions& options,
                                         const physics::ControlProgram& hint = {});

// Re-simulates a program under the cap from start_clock_s + wait_s (fine step, RK4).
physics::SimulationResult simulate_capped(const SectionEngine& engine,
                                          const physics::ControlProgram& program,
                                          const physics::SpeedCap& cap, double start_clock_s,
                                          double resim_step_m);

}  // namespace ecorail::dp
