// Runs of a few phases, searched on the simulator, for one part of a timing-point journey
// (dp/timing_journey_part.hpp), where the time-price search is weak:
// - A part slower than any time price gives. A part that starts moving fast and must end at
//   rest late, or at a high speed late (a point pinning the state), has an energy that rises
//   with its running time beyond its least-energy run: slowing down costs the kinetic energy
//   the run must win back, and that cost is concave in the time (on level track about
//   C - m L^2 / (2 eta T^2)). No non-negative time price reaches such a run, and no negative
//   one either (the Lagrangian then jumps to the grid's crawl), so the price searches end early
//   and the part's time was missed. FamilySet::Slowing: brake or coast down, hold or coast,
//   then win the end's speed back (full traction, or coast or brake to it, or hold from where
//   a coast reaches it; brake to rest for a stop).
// - A part that ends at one speed (a point pinning the state, or a zero-width speed window),
//   whose grid run has to be moved onto it on the simulator: FamilySet::Any adds full traction
//   first, then a coast or a hold, then the last phase (the structure such a run has on level
//   track), from the part's last passing point on, and the cheaper run is kept.
// Each family has two positions, the end of its first phase and the start of its last,
// bisected on re-simulated runs for the arrival time and the end speed. Feasible, checked on
// the engine's fine step; not proven the least energy on every track (docs/ttobench.md, "A
// part slower than its prices").
#pragma once

#include <optional>

#include "dp/section_engine.hpp"
#include "dp/timing_journey_part.hpp"
#include "physics/simulator.hpp"

namespace ecorail::dp::timing {

enum class FamilySet { Slowing, Any };

// The cheapest run of the families of `set` from start that arrives target_s after it (within
// kZeroWidthTime_s) and ends as end asks (a zero-width end speed within kZeroWidthSpeed_ms);
// nullopt when none does. The runs follow `lead` (a program from the start) up to from_m and
// change only after it (a part's last passing point: the run before it meets the windows
// there). Every simulation adds one to *evaluations.
std::optional<LambdaRun> family_run(const SectionEngine& engine, const StartState& start,
                                    const EndCheck& end, double target_s,
                                    const physics::ControlProgram& lead, double from_m,
                                    FamilySet set, int* evaluations);

}  // namespace ecorail::dp::timing
