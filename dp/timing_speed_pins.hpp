// Passing points that ask for one speed at a time they leave free (a speed window of zero
// width, a time window of some width), for the timing-point journey solver
// (dp/timing_journey.hpp). The part search holds such a window by a speed band on its grid, a
// band one speed step wide either side that the run is then moved into on the simulator; with
// two such points in a part, or one before a point pinning the state, that run could cost
// 5-30 % more than a feasible run through the same windows (random journeys around witness
// runs, docs/ttobench.md, "One speed at a free time"). Such a point is the same as a point
// pinning the state once its time is known, and a point pinning the state splits the journey
// into parts that couple only through that time, as a stop does. So each is pinned in turn,
// its time chosen by golden section between the times the run passes the points either side
// (each evaluation one solve of the part that holds it, from its departure), and the journey
// is kept so when it costs less than the plain search's run. Where the plain search misses a
// window, or runs the part that holds it by the label search (a heuristic's energy), a point
// that asks for one time at a speed it leaves free is pinned the same way, its speed searched
// within half the run's speed there either side; a part that a pin leaves to the label search
// has its own such points pinned next.
#pragma once

#include <vector>

#include "dp/timing_journey.hpp"
#include "dp/timing_pin_trials.hpp"

namespace ecorail::dp::timing {

// Whether w asks for one speed above 0 at a time it leaves free.
bool asks_one_speed_at_a_free_time(const TimingWindow& w);
// Whether w asks for one time at a speed it leaves free (a passing point).
bool asks_one_time_at_a_free_speed(const TimingWindow& w);

// plain is `windows` solved (by solve). Where windows has passing points that ask for one
// speed at a free time, or (plain missing a window, or a part of plain run by the label search)
// one time at a free speed (at most kMaxSpeedPins, on a journey of at most kSpeedPinReach_m),
// the journey with them pinned as above, when every window holds on it and it costs less than
// plain; plain otherwise. Its windows are reported as asked; its evaluations and wall time count
// every solve, also when plain is returned. trial_solve solves the golden section's trials (a
// coarser grid); refused narrows a time's bracket to the times a run can meet before the golden
// section starts.
TimingJourneySolution with_speeds_pinned(const std::vector<TimingWindow>& windows,
                                         TimingJourneySolution plain, const JourneySolve& solve,
                                         const JourneySolve& trial_solve,
                                         const JourneyRefused& refused);

}  // namespace ecorail::dp::timing
