// Starts for the headway search built from the maximisers of a relaxed problem (the window
// bound's Lagrangian DP, window_bound.hpp): the DP prices the fixed span instead of keeping it,
// so its headway sequences sum to a little more or less than the span. repair_to_span moves
// them onto the span with the least change: one second at a time off the longest headways (or
// onto the shortest), every headway kept in range, so the structure the relaxation found (which
// headways are short, which long) is kept for the annealing to start from.
#pragma once

#include <vector>

#include "timetable/fleet_problem.hpp"

namespace ecorail::timetable {

// Headways within [headway_min_s, headway_max_s] summing to span_s, as close to the given ones
// as whole seconds allow (one class only). Throws std::invalid_argument when the count is wrong
// or no such sequence exists.
std::vector<int> repair_to_span(std::vector<int> headways_s, const FleetProblem& problem);

}  // namespace ecorail::timetable
