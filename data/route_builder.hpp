// Builds the physics::Route between two stations of a Line, in the direction of travel: the
// position runs from 0 at the departure station, gradients change sign when the train runs
// towards decreasing kilometre posts, and the three tables are merged into segments of constant
// gradient, curve and limit. Errors (unknown station, same station twice, a stretch the tables
// do not cover) are InputErrors naming file and row; a limit above the train's maximum speed is
// capped at that maximum.
#pragma once

#include <string>
#include <vector>

#include "data/line.hpp"
#include "physics/route.hpp"
#include "physics/train.hpp"

namespace ecorail::data {

physics::Route build_route(const Line& line, const std::string& from, const std::string& to,
                           const physics::Train& train);

// The stops of a run from `from` to `to` stopping at every station between them, both ends
// included, in the order of travel (the stations file's order, or its reverse).
std::vector<std::string> stops_between(const Line& line, const std::string& from,
                                       const std::string& to);

// The routes of a run over `stops` (at least two), one per leg between consecutive stops, in
// the order of travel: the section list of a journey.
std::vector<physics::Route> build_routes(const Line& line, const std::vector<std::string>& stops,
                                         const physics::Train& train);

}  // namespace ecorail::data
