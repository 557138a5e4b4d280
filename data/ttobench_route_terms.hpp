// The route terms TTOBench tracks and trains need beyond the plain route builder: curvature
// that varies linearly along a row (clothoids), Roeckl's curve resistance, tunnel drag from the
// train's table by cross-section, and a train length (a limit holds until the tail has passed;
// gradient, curve and tunnel forces are averaged over the train, the track behind the line's
// start continuing its first value). The forces vary continuously where a clothoid or a change
// lies under the train; the route then gets pieces of at most kMaxPiece_m, each with the exact
// mean of the force over the piece, so the work the train does over every piece is exact.
// data/route_builder calls it only when a line or train uses one of these terms, so existing
// routes are unchanged.
#pragma once

#include <vector>

#include "data/line.hpp"
#include "physics/route.hpp"
#include "physics/train.hpp"

namespace ecorail::data {

inline constexpr double kMaxPiece_m = 5.0;

bool needs_route_terms(const Line& line, const physics::Train& train);

// Curve resistance in N/kN for a curvature magnitude |k| (1/m; 0 = straight). Roeckl needs
// R > 55 m (callers check).
double curve_resistance_N_per_kN(double abs_curvature_per_m, CurveFormula formula);

// Segments of the route that starts at km post p0_m and runs length_m in direction dir (+1:
// increasing km posts). InputError for a tunnel whose cross-section the train's table does not
// cover (or a train without one), and for a radius Roeckl's formula cannot take.
std::vector<physics::RouteSegment> route_term_segments(const Line& line, double p0_m, int dir,
                                                       double length_m,
                                                       const physics::Train& train);

}  // namespace ecorail::data
