// The forward simulator: drives a train along a route under a control law, at a fine position
// step, with events at every route change (gradient, curve, limit), at every switch point of
// the control law and at the stop. Every figure a user is told (energy, running time, stop
// position, overspeed) is measured here, never taken from an optimiser's own bookkeeping.
#pragma once

#include <functional>
#include <vector>

#include "physics/control.hpp"
#include "physics/energy_ledger.hpp"
#include "physics/motion.hpp"

namespace ecorail::physics {

struct TracePoint {
  double t_s = 0.0;
  double s_m = 0.0;
  double v_ms = 0.0;
  double accel_m_s2 = 0.0;  // mean over the step that ends here
  double force_N = 0.0;     // mean applied force over the step that ends here
  Regime regime = Regime::Coast;
};

// A control program: from each position on, a control, until the next entry.
struct ProgramStep {
  double from_m = 0.0;
  Control control = Control::Coast;
};
using ControlProgram = std::vector<ProgramStep>;

// A feedback law: the control to apply at position s and speed v.
using ControlLaw = std::function<Control(double s_m, double v_ms)>;

struct SimulationOptions {
  double step_m = 0.05;
  int rk_order = 4;
  double start_speed_ms = 0.0;
  double start_position_m = 0.0;
};

struct SimulationResult {
  std::vector<TracePoint> trace;
  EnergyLedger energy;
  double running_time_s = 0.0;
  double end_position_m = 0.0;  // where the train came to rest (or route end if still moving)
  double end_speed_ms = 0.0;
  double stop_error_m = 0.0;      // end position minus route length
  double max_overspeed_ms = 0.0;  // largest excess over the line's static limit
  bool stopped_early = false;     // came to rest before the end of the route
};

// Runs a feedback law; the law is queried once per step and steps end at each breakpoint.
SimulationResult simulate(const Motion& motion, const ControlLaw& law,
                          const std::vector<double>& breakpoints_m, const SimulationOptions& opt);
// Runs a control program (a law that switches at fixed positions).
SimulationResult simulate(const Motion& motion, const ControlProgram& program,
                          const SimulationOptions& opt);

}  // namespace ecorail::physics
