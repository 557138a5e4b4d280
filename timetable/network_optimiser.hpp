// Headway optimisation under the network model (--model network): the departures that
// minimise the substations' energy on the traction power network. The same search as for
// power-flow (headway_optimiser.hpp), on the network's objective: starts from the uniform
// timetable and from the exact optimum of the two-train approximation (every headway valued by
// the substation energy of two trains that far apart alone on the network), simulated annealing
// from each start on a coarse grid (anneal_step_s, default 1 s) with incremental re-evaluation
// (NetworkBalance: a move re-solves only the instants the moved train touches), runs spread over
// OpenMP threads with counter-based random numbers (the result does not depend on the thread
// count), then a polish on the coarse grid (every train tried within +-polish_window_s) and one
// on the model's own grid (+-2 s). A time limit stops the annealing at 60 % of it and the polish
// (between trains) at the limit; the result is then NO_CONVERGENCE. With peak windows
// (question 2.2's day) the start is the windowed DP's optimum of the same two-train values and
// every move keeps both headways it changes in their class, as in the power-flow search. The
// summary states a lower bound on the substation energy (network_bound.hpp) and the gap to it.
// optimise_headways() calls this for the network model.
#pragma once

#include "timetable/headway_optimiser.hpp"

namespace ecorail::timetable {

HeadwayOptimiserResult optimise_network_headways(const FleetModels& models,
                                                 const HeadwayOptimiserOptions& options);

}  // namespace ecorail::timetable
