// Route: the track between two stations as the train sees it, in its own direction of travel.
// Position s runs from 0 (departure stop) to length_m (arrival stop). The route is a list of
// contiguous segments over which gradient (per mille, positive = uphill in the travel
// direction), curve radius and speed limit are constant. The direction of travel is resolved
// once, when the route is built from a line (data/route_builder); nothing downstream knows
// about kilometre posts except for the km_post_m() label used in reports.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace ecorail::physics {

struct RouteSegment {
  double start_m = 0.0;
  double end_m = 0.0;
  double gradient_permille = 0.0;  // uphill positive, in the travel direction
  double curve_radius_m = 0.0;     // 0 = straight
  double speed_limit_ms = 0.0;
  // Curve resistance in N/kN when it is not 600 / curve_radius_m (< 0: it is): another formula
  // (Roeckl), a clothoid's mean, or the mean over a train's length (data/route_builder).
  double curve_N_per_kN = -1.0;
  // Tunnel drag: added Davis C in N/kN per (km/h)^2 (0 outside tunnels); see Motion.
  double tunnel_drag_N_per_kN_kmh2 = 0.0;

  // Specific track resistance in N/kN: gradient plus curve (600 / R or curve_N_per_kN).
  double track_N_per_kN() const;
};

class Route {
 public:
  Route() = default;
  // Segments must be contiguous, start at 0 and have positive length.
  Route(std::vector<RouteSegment> segments, double origin_km_post_m, int km_post_direction,
        std::string from_name, std::string to_name);

  double length_m() const { return segments_.empty() ? 0.0 : segments_.back().end_m; }
  const std::vector<RouteSegment>& segments() const { return segments_; }
  // Index of the segment holding s; a boundary belongs to the segment that starts there.
  std::size_t index_at(double s_m) const;
  const RouteSegment& at(double s_m) const { return segments_[index_at(s_m)]; }
  // The same index, first trying segment `hint` and the one after it (a cursor along a run:
  // O(1) when the positions asked for move forward); any hint gives the same answer.
  std::size_t index_at(double s_m, std::size_t hint) const {
    const std::size_t n = segments_.size();
    for (std::size_t i = hint; i < n && i <= hint + 1; ++i) {
      if (segments_[i].start_m <= s_m && (i + 1 == n || s_m < segments_[i + 1].start_m)) return i;
    }
    return index_at(s_m);
  }
  // Speed limit at s; at a boundary the stricter of the two neighbouring limits applies.
  double speed_limit_ms(double s_m) const;
  // Kilometre post of position s (a label for reports).
  double km_post_m(double s_m) const { return origin_km_post_m_ + km_post_direction_ * s_m; }
  const std::string& from_name() const { return from_; }
  const std::string& to_name() const { return to_; }
  // Interior positions where gradient, curve or limit changes.
  std::vector<double> change_points_m() const;

 private:
  std::vector<RouteSegment> segments_;
  double origin_km_post_m_ = 0.0;
  int km_post_direction_ = 1;
  std::string from_, to_;
};

// The stretch [from_m, to_m] of route as a route of its own (positions from 0, kilometre posts
// and direction kept, its ends named by their positions in route, "1500.0 m"): a journey's
// part between two timing points.
Route slice_route(const Route& route, double from_m, double to_m);

// The fields of every segment of the route, in order: two routes drive alike (same speed
// envelope, motion and hence the same DP tables and runs) exactly when their tracks are equal.
// Names and kilometre posts are labels and are not part of it. A key for maps of twins.
std::vector<double> track_key(const Route& route);

}  // namespace ecorail::physics
