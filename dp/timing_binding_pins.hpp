// The parts of a timing-point journey that the label search ran (dp/timing_label_search.hpp,
// the last resort where every price search missed a window), re-solved between pinned states.
// The label search's run is feasible but its energy is a heuristic's: 39 % above a witness run
// on a part held back twice (tests/dp/test_timing_label_search.cpp), 7.9 % above an independent
// witness on `hb2` (tests/cli/held_back_twice.sh). Where that run passes a point at (within
// kBindingSlack_s of) one of its time bounds, the bound binds, and a point whose time and speed
// are fixed splits the part in two that couple only through that speed, as a stop splits a
// journey; each piece is then a part from one pinned state to another, which the price searches
// meet exactly. So every such point is pinned at its bound with the run's speed there, and the
// speeds are searched jointly. The stretch's energy is then a sum along a chain, one piece
// between each two pins, each a function of the speeds at its two ends, so the search is a
// lattice of speeds moved and refined with a DP along the chain (dp/chain_lattice_search.hpp):
// every speed moves at once (two points 100 m apart that must be 9 s apart want the same speed,
// which a search of one speed at a time does not find), and each lattice costs only the
// solves of its new pieces (none after a piece that no run meets). The journey at the best speeds
// replaces the label search's when every window holds on it and it costs less. Not exact: the times
// stay at the bounds the label run touched, and the speeds are a local search's.
#pragma once

#include <vector>

#include "dp/timing_journey.hpp"
#include "dp/timing_speed_pins.hpp"

namespace ecorail::dp::timing {

// solution is `windows` solved (by solve). Where a part of it was run by the label search and
// that run binds one to kMaxBindingPins time bounds of the points inside it, the journey with
// those points pinned (see above) when it costs less and every window holds; solution
// otherwise. Its windows are reported as asked; its evaluations and wall time count every solve.
// search_solve solves the search's trials (the asked grid, no label search), up to `threads` at
// once (0: OpenMP's default; the result is the same for any count), so it must be thread-safe.
TimingJourneySolution with_label_runs_pinned(const std::vector<TimingWindow>& windows,
                                             TimingJourneySolution solution,
                                             const JourneySolve& solve,
                                             const JourneySolve& search_solve, int threads);

}  // namespace ecorail::dp::timing
