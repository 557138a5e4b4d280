// Whether two lines give the same runs: for every section between adjacent stations of the
// first line, the routes both lines build for a train (data/route_builder.hpp) have the same
// length and, everywhere along it, the same gradient, curve resistance, speed limit and tunnel
// drag. Two descriptions of one line can differ in their tables (rows merged, curves as radii
// or as curvature, km posts shifted) and still drive alike; this is the test an export must
// pass before it is written (`ecorail export`), where a checksum of the tables would refuse a
// faithful translation.
#pragma once

#include <string>

#include "data/line.hpp"
#include "physics/route.hpp"
#include "physics/train.hpp"

namespace ecorail::data {

// Empty when the routes agree within tolerance_rel (relative, 1 m/km of length); otherwise
// where and what first differs, e.g. "gradient at 1234.5 m: 2.000 vs 3.000 per mille".
std::string route_difference(const physics::Route& a, const physics::Route& b,
                             double tolerance_rel = 1e-9);
// Empty when every section of `a` (adjacent stations in km order) is the same in `b` (stations
// by name); otherwise the section and route_difference's text.
std::string line_runs_difference(const Line& a, const Line& b, const physics::Train& train,
                                 double tolerance_rel = 1e-9);

}  // namespace ecorail::data
