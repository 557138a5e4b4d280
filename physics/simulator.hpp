// The forward simulator: drives a train along a route under a control law, at a fine position
// step, with events at every route change (gradient, curve, limit), at every switch point of
// the control law and at the stop. Every figure a user is told (energy, running time, stop
// position, overspeed) is measured here, never taken from an optimiser's own bookkeeping.
#pragma once

#include <cstddef>
#include <functional>
#include <limits>
#include <vector>

#include "base/big_blocks.hpp"
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

// A moving speed cap: the highest speed allowed at clock time t and position s (route
// coordinates), in addition to the line's static limits; +infinity where it does not bind. The
// separation behind a train ahead, v <= sqrt(2 L b), is one. The simulator supervises it as it
// supervises the speed envelope: when the control would end a step above the cap, the force is
// reduced (down to full braking) so the train lands on it, and it follows the cap while the cap
// binds. The cap must be one the train can follow with its braking (a braking curve no steeper
// than the train's own, as sqrt(2 L b) is when b does not exceed the train's braking
// deceleration); where it is not, the excess is measured and reported, never hidden. A cap of
// zero holds a standing train: it waits, the clock running, until the cap lifts.
using SpeedCap = std::function<double(double t_s, double s_m)>;

struct SimulationOptions {
  double step_m = 0.05;
  int rk_order = 4;
  double start_speed_ms = 0.0;
  double start_position_m = 0.0;
  SpeedCap speed_cap;          // empty: none
  double start_clock_s = 0.0;  // clock time of the start (the cap's time axis)
  double wait_step_s = 0.5;    // while held at rest by the cap
  double max_wait_s = 3600.0;  // held longer than this: the run ends there (stopped_early)
};

// A run that comes to rest within this of the end of its route has arrived (its stop error is
// reported and checked by the solvers); further short, it stopped early. The stop is located
// inside a substep by proportion, and braking into it on the speed envelope (99.98 % of full
// force) can end a millimetre or so short: at 1 mm, every run of a 3 km level section on a
// 10 m grid counted as stopped early, and the running-time search failed.
inline constexpr double kArrivalSlack_m = 0.01;

// The running state of a program run without a speed cap at the start of one of its steps,
// kept every kCheckpointSteps steps so that a re-simulation of an edited program can resume
// from it (see simulate() with an earlier run). e is the integrator's state itself, not
// recomputed from the trace's speed (v^2 / 2 would not give back the same bits).
struct SimulationCheckpoint {
  std::size_t trace_size = 0;  // trace points written before this step
  double s_m = 0.0;
  double e = 0.0;
  double t_s = 0.0;
  EnergyLedger energy;
  double max_overspeed_ms = 0.0;
};
inline constexpr std::size_t kCheckpointSteps = 256;

struct SimulationResult {
  BigVector<TracePoint> trace;
  EnergyLedger energy;
  double running_time_s = 0.0;
  double end_position_m = 0.0;  // where the train came to rest (or route end if still moving)
  double end_speed_ms = 0.0;
  double stop_error_m = 0.0;      // end position minus route length
  double max_overspeed_ms = 0.0;  // largest excess over the line's static limit
  bool stopped_early = false;     // came to rest before the end of the route (kArrivalSlack_m)
  // With a moving speed cap: the largest excess over it (<= 0 when respected), the distance
  // over which it bound, and the time spent held at rest by it.
  double max_cap_overspeed_ms = -std::numeric_limits<double>::infinity();
  double cap_binding_m = 0.0;
  double cap_wait_s = 0.0;
  // Resumable state (program runs without a speed cap only; empty otherwise), with the program
  // and options that produced it: a resumed run must use the same step, order and start. (The
  // program is kept because callers may pair a run with a simplified program, whose steps end
  // elsewhere.)
  std::vector<SimulationCheckpoint> checkpoints;
  ControlProgram checkpoint_program;
  // The motion it ran on, as an identity only: a run of another motion is never reused.
  const Motion* checkpoint_motion = nullptr;
  double checkpoint_step_m = 0.0;
  int checkpoint_rk_order = 0;
  double checkpoint_start_speed_ms = 0.0;
  double checkpoint_start_position_m = 0.0;
};

// Runs a feedback law; the law is queried once per step and steps end at each breakpoint.
SimulationResult simulate(const Motion& motion, const ControlLaw& law,
                          const std::vector<double>& breakpoints_m, const SimulationOptions& opt);
// Runs a control program (a law that switches at fixed positions).
SimulationResult simulate(const Motion& motion, const ControlProgram& program,
                          const SimulationOptions& opt);

// Where two programs first differ: the smaller position of the first entry that is not the
// same in both (position and control); +infinity for equal programs, -infinity when their
// first entries differ.
double first_difference_m(const ControlProgram& a, const ControlProgram& b);

// Runs `program` as simulate(motion, program, opt) does, bit for bit, reusing `earlier`: a
// run of another program (earlier.checkpoint_program) on the same motion with the same options.
// Every step of the earlier run that ends strictly before the programs' first difference is
// the same step in the new run (the same control, the same events: steps end at program
// entries and route changes), so the new run resumes from the last checkpoint before it and
// copies the trace up to there. Falls back to a full run when there is no such checkpoint,
// with a speed cap, or when `earlier` was made with another motion or other options.
SimulationResult simulate(const Motion& motion, const ControlProgram& program,
                          const SimulationOptions& opt, const SimulationResult& earlier);

// What of `run` a resume can use before position up_to_m: its checkpoints before there and
// its trace up to the last of them, with the program, motion and options (the run's other
// figures are not kept). Resuming from it is as exact as from the whole run; it reaches no
// further than up_to_m, and it is much smaller to keep.
SimulationResult resume_prefix(const SimulationResult& run, double up_to_m);

}  // namespace ecorail::physics
