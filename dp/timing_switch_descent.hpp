// Descent on the switch positions of a part's run, for a part of a timing-point journey that
// ends at one speed at one time, or at a stop (dp/timing_journey_part.hpp): the grid's run (moved
// onto the end's speed), or a run of a few phases (dp/timing_family_run.hpp), keeps the shape it
// was found with, and a run of that shape with its switches elsewhere can be cheaper (traction
// that the end's braking envelope brakes back, a hold where a longer traction and a coast would
// do, a coast that enters a lower limit a grid step away from where it should). Every switch
// after from_m is a variable; the arrival time is an equation, a zero-width end speed a second
// one, and each held passing point one or two more (its time, its speed: a zero-width window,
// or one the run meets at a bound, held where the run meets it). An end speed the braking
// envelope holds, whatever a switch does, is left to the envelope; so is the stop, and a
// switch whose move one way stops the run short is differenced the other way. Each round takes the
// gradient of the cost and the Jacobian of the equations by finite differences on the simulator,
// steps along the gradient projected onto the equations' tangent, restores the equations by Newton
// steps with that Jacobian (each switch weighted by its room, as in the Newton step that meets
// windows), and keeps the run only when it costs less and meets both; a refused step is tried again
// shorter, and where the gradient no longer gains (a kink: the envelope, a limit) one switch at a
// time is tried either way. The search runs at a coarse step (2 m) and its run is finished at the
// engine's fine step, back onto both equations there (the time within half of kZeroWidthTime_s, the
// speed within half of kZeroWidthSpeed_ms). So the result is never dearer than the run it starts
// from; a run that misses the equations (a phase added to a shape) is first brought onto them.
// It is a local optimum of the run's shape, not a proof of the least energy.
#pragma once

#include <cmath>
#include <optional>
#include <vector>

#include "dp/section_engine.hpp"
#include "dp/timing_journey_part.hpp"

namespace ecorail::dp::timing {

struct SwitchDescentOptions {
  int max_rounds = 40;         // gradient evaluations
  int max_simulations = 600;   // all the re-simulations of one descent
  double first_move_m = 8.0;   // the largest switch move of the first step
  double least_move_m = 0.02;  // steps shorter than this end the descent
  double difference_m = 0.25;  // finite-difference step of a switch
  double search_step_m = 2.0;  // RK4 step of the search's runs (the result is finished at the
                               // engine's fine step)
  bool IsValid() const {
    return max_rounds > 0 && max_simulations > 0 && first_move_m > least_move_m &&
           least_move_m > 0.0 && difference_m > 0.0 && search_step_m > 0.0;
  }
};

struct SwitchDescentResult {
  std::optional<LambdaRun> run;  // cheaper than the run given, meeting its time and end speed
  int simulations = 0;
  int rounds = 0;
};

// A passing point the descent holds: its time and/or its speed (NaN: free) at s_m, relative to
// the part's start (a zero-width window, or a window the run meets at a bound).
struct HeldPassing {
  double s_m = 0.0;
  double time_s = NAN, speed_ms = NAN;
};

// From run (which must end as end asks, target_s after the start): moves only the switches
// after from_m, holding each of `held` as one or two more equations.
SwitchDescentResult descend_switches(const SectionEngine& engine, const StartState& start,
                                     const EndCheck& end, double target_s, const LambdaRun& run,
                                     double from_m, const SwitchDescentOptions& options = {},
                                     const std::vector<HeldPassing>& held = {});

}  // namespace ecorail::dp::timing
