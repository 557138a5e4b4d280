// A run slower than any time price gives, for one part of a timing-point journey
// (dp/timing_journey_part.hpp). A part that starts moving fast and must end at rest late, or at
// a high speed late (a point pinning the state), has an energy that rises with its running time
// beyond its least-energy run: slowing down costs the kinetic energy the run must win back, and
// that cost is concave in the time (on level track about C - m L^2 / (2 eta T^2)). No
// non-negative time price reaches such a run, and no negative one either (the Lagrangian then
// jumps to the grid's crawl), so the price searches end early and the part's time is missed.
// The runs here are the structure such an optimum has on level track: coast from the start
// (or, when coasting cannot slow it enough, brake) down to a speed, hold that speed, then win
// the end's speed back with full traction (or coast, or brake, to it; brake to rest for a stop).
// Two positions, the start of the hold and of the last phase, are bisected on re-simulated runs
// for the arrival time and the end speed. Feasible, checked on the engine's fine step; not
// proven the least energy on every track (docs/ttobench.md, "A part slower than its prices").
#pragma once

#include <optional>

#include "dp/section_engine.hpp"
#include "dp/timing_journey_part.hpp"
#include "physics/simulator.hpp"

namespace ecorail::dp::timing {

// The cheapest run of the families above from start that arrives target_s after it (within
// kZeroWidthTime_s) and ends as end asks (a zero-width end speed within kZeroWidthSpeed_ms);
// nullopt when none does. The runs follow `lead` (a program from the start) up to from_m and
// slow down only after it (a part's last passing point: the faster run before it meets the
// windows there). Every simulation adds one to *evaluations.
std::optional<LambdaRun> slow_run(const SectionEngine& engine, const StartState& start,
                                  const EndCheck& end, double target_s,
                                  const physics::ControlProgram& lead, double from_m,
                                  int* evaluations);

}  // namespace ecorail::dp::timing
