// Policy extraction: turns a value function into a control program with continuous switch
// points. Starting from rest, the train is driven forward; at each decision point every control
// is scored by integrating it to the next grid position and adding the interpolated
// cost-to-go there (a one-step look-ahead on the DP's value function, valid at any off-grid
// state). When the best control changes, the switch position is located by bisection, so the
// program's switch points (and so its running time) vary continuously with lambda instead of
// jumping from grid point to grid point.
#pragma once

#include <functional>

#include "dp/backward_sweep.hpp"
#include "dp/objective.hpp"
#include "physics/motion.hpp"
#include "physics/simulator.hpp"
#include "physics/speed_envelope.hpp"

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

// Cruising as a speed hold. On a long stretch where the optimum is to cruise, the grid's
// optimum can instead alternate full traction and coasting in a narrow band of speed (a saw
// tooth: on a 48.5 km TTOBench run, 411 traction and 411 coasting phases between 128 and
// 133 km/h). A driver cannot follow that, and it is no cheaper: at the same mean speed a hold
// covers the stretch in the same time against the least resistance. So a run of alternating
// traction and coasting whose switch speeds swing up and down at least min_swings times inside
// a band of at most max_band_kmh (and max_band_fraction of its mean speed) is replaced by one
// hold at the band's mean speed (distance over time): the control before it runs on until the
// train reaches that speed, the hold follows, and the last phase of the run (e.g. the final
// coast) starts where it did.
struct CruiseSettings {
  int min_swings = 3;
  double max_band_kmh = 10.0;
  double max_band_fraction = 0.10;
};

// The program with every such oscillation replaced by a hold, or the program unchanged when it
// has none. sim is the program's re-simulation (the speeds at its switch points).
physics::ControlProgram hold_cruising(const physics::ControlProgram& program,
                                      const physics::SimulationResult& sim,
                                      const CruiseSettings& settings = {});

// A hold never brakes below the speed limit. Where a hold (a cruise hold_cruising made, or the
// grid's own) would need braking to keep its speed, on a descent where gravity outweighs the
// resistance, braking throws away energy the descent gives for free: the optimum coasts and
// lets the speed rise (up to the limit, where the envelope brakes), and holds again once the
// speed is back down. Without this, a 10 km descent of -10 per mille under a 140 km/h cruise was
// braked through and the run cost 12 % more than the grid's own. simulate re-simulates a
// program; each replaced braking stretch costs two re-simulations, at most max_rounds of them.
// sim is the program's re-simulation and is replaced by the returned program's.
physics::ControlProgram coast_instead_of_braking_holds(
    const physics::ControlProgram& program, physics::SimulationResult& sim,
    const physics::SpeedEnvelope& envelope,
    const std::function<physics::SimulationResult(const physics::ControlProgram&)>& simulate,
    int max_rounds = 16);

// Drops every entry (but the first) shorter than min_length_m or lasting less than
// min_duration_s in sim (0: no limit of that kind); the control before it runs on, and
// neighbours with the same control merge. merged (if given) receives the number dropped.
physics::ControlProgram merge_short_entries(const physics::ControlProgram& program,
                                            const physics::SimulationResult& sim,
                                            double min_length_m, double min_duration_s,
                                            int* merged = nullptr);

// Drops entries shorter than min_entry_m and merges repeated controls.
physics::ControlProgram simplify_program(const physics::ControlProgram& program,
                                         double min_entry_m);

physics::ControlProgram extract_program(const physics::Motion& motion, const StageGrid& grid,
                                        const ValueFunction& value, Objective objective,
                                        const ExtractionSettings& settings);

}  // namespace ecorail::dp
