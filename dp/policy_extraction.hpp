// Policy extraction: turns a value function into a control program with continuous switch
// points. Starting from rest, the train is driven forward; at each decision point every control
// is scored by integrating it to the next grid position and adding the interpolated
// cost-to-go there (a one-step look-ahead on the DP's value function, valid at any off-grid
// state). When the best control changes, the switch position is located by bisection, so the
// program's switch points (and so its running time) vary continuously with lambda instead of
// jumping from grid point to grid point.
#pragma once

#include "dp/backward_sweep.hpp"
#include "dp/objective.hpp"
#include "physics/motion.hpp"
#include "physics/simulator.hpp"

namespace ecorail::dp {

struct ExtractionSettings {
  double decision_step_m = 1.0;
  int bisections = 8;
  // Relative margin by which a challenger must beat the incumbent control (hysteresis against
  // chattering between controls whose look-ahead costs are equal to rounding).
  double tie_tolerance = 1e-7;
  // Program entries shorter than this are dropped (the control before them goes on): they are
  // integration-level dithering between nearly equal controls, and they would pin the
  // neighbouring switch points that the running-time trim moves.
  double min_entry_m = 1.0;
  physics::StepSettings dp_step;  // the same integration as the transition table
  // Where the train is when the program starts (a restart mid-run); at rest at 0 by default.
  double start_position_m = 0.0;
  double start_speed_ms = 0.0;
};

// Drops entries shorter than min_entry_m and merges repeated controls.
physics::ControlProgram simplify_program(const physics::ControlProgram& program,
                                         double min_entry_m);

physics::ControlProgram extract_program(const physics::Motion& motion, const StageGrid& grid,
                                        const ValueFunction& value, Objective objective,
                                        const ExtractionSettings& settings);

}  // namespace ecorail::dp
