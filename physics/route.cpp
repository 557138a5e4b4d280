#include "physics/route.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace ecorail::physics {

double RouteSegment::track_N_per_kN() const {
  const double curve = curve_N_per_kN >= 0.0  ? curve_N_per_kN
                       : curve_radius_m > 0.0 ? 600.0 / curve_radius_m
                                              : 0.0;
  return gradient_permille + curve;
}

Route::Route(std::vector<RouteSegment> segments, double origin_km_post_m, int km_post_direction,
             std::string from_name, std::string to_name)
    : segments_(std::move(segments)),
      origin_km_post_m_(origin_km_post_m),
      km_post_direction_(km_post_direction),
      from_(std::move(from_name)),
      to_(std::move(to_name)) {
  if (segments_.empty()) throw std::invalid_argument("route has no segments");
  double expect = 0.0;
  for (const auto& seg : segments_) {
    if (std::abs(seg.start_m - expect) > 1e-9 || !(seg.end_m > seg.start_m)) {
      throw std::invalid_argument("route segments must be contiguous from 0 with positive length");
    }
    expect = seg.end_m;
  }
}

std::size_t Route::index_at(double s_m) const {
  auto it = std::upper_bound(segments_.begin(), segments_.end(), s_m,
                             [](double s, const RouteSegment& seg) { return s < seg.start_m; });
  if (it == segments_.begin()) return 0;
  return static_cast<std::size_t>(it - segments_.begin()) - 1;
}

double Route::speed_limit_ms(double s_m) const {
  const std::size_t i = index_at(s_m);
  double v = segments_[i].speed_limit_ms;
  if (i > 0 && s_m == segments_[i].start_m) v = std::min(v, segments_[i - 1].speed_limit_ms);
  return v;
}

std::vector<double> Route::change_points_m() const {
  std::vector<double> points;
  for (std::size_t i = 1; i < segments_.size(); ++i) points.push_back(segments_[i].start_m);
  return points;
}

Route slice_route(const Route& route, double from_m, double to_m) {
  std::vector<RouteSegment> out;
  for (const auto& seg : route.segments()) {
    const double a = std::max(seg.start_m, from_m), b = std::min(seg.end_m, to_m);
    if (b - a <= 1e-9) continue;
    RouteSegment s = seg;
    s.start_m = a - from_m;
    s.end_m = b - from_m;
    out.push_back(s);
  }
  if (!out.empty()) {
    out.front().start_m = 0.0;
    out.back().end_m = to_m - from_m;
  }
  const int direction = route.km_post_m(1.0) >= route.km_post_m(0.0) ? 1 : -1;
  auto name = [](double m) {
    char text[64];
    std::snprintf(text, sizeof text, "%.1f m", m);
    return std::string(text);
  };
  return Route(std::move(out), route.km_post_m(from_m), direction, name(from_m), name(to_m));
}

std::vector<double> track_key(const Route& route) {
  std::vector<double> key;
  key.reserve(7 * route.segments().size());
  for (const RouteSegment& s : route.segments()) {
    key.insert(key.end(), {s.start_m, s.end_m, s.gradient_permille, s.curve_radius_m,
                           s.speed_limit_ms, s.curve_N_per_kN, s.tunnel_drag_N_per_kN_kmh2});
  }
  return key;
}

}  // namespace ecorail::physics
