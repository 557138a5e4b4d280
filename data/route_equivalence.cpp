#include "data/route_equivalence.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <vector>

#include "data/route_builder.hpp"

namespace ecorail::data {

namespace {

bool close(double x, double y, double tolerance_rel) {
  return std::abs(x - y) <= tolerance_rel * std::max({1.0, std::abs(x), std::abs(y)});
}

std::string differs(const char* what, double s_m, double x, double y, const char* unit) {
  char buf[160];
  std::snprintf(buf, sizeof buf, "%s at %.3f m: %.6g vs %.6g %s", what, s_m, x, y, unit);
  return buf;
}

}  // namespace

std::string route_difference(const physics::Route& a, const physics::Route& b,
                             double tolerance_rel) {
  if (!close(a.length_m(), b.length_m(), tolerance_rel))
    return differs("length", 0.0, a.length_m(), b.length_m(), "m");
  // Every piece between the change points of either route is constant in both: compare at
  // each piece's middle.
  std::vector<double> cuts = a.change_points_m();
  const std::vector<double> more = b.change_points_m();
  cuts.insert(cuts.end(), more.begin(), more.end());
  cuts.push_back(0.0);
  cuts.push_back(a.length_m());
  std::sort(cuts.begin(), cuts.end());
  for (std::size_t i = 0; i + 1 < cuts.size(); ++i) {
    if (!(cuts[i + 1] - cuts[i] > 1e-6)) continue;
    const double s = 0.5 * (cuts[i] + cuts[i + 1]);
    const physics::RouteSegment& x = a.at(s);
    const physics::RouteSegment& y = b.at(s);
    if (!close(x.gradient_permille, y.gradient_permille, tolerance_rel))
      return differs("gradient", s, x.gradient_permille, y.gradient_permille, "per mille");
    const double cx = x.track_N_per_kN() - x.gradient_permille;
    const double cy = y.track_N_per_kN() - y.gradient_permille;
    if (!close(cx, cy, tolerance_rel)) return differs("curve resistance", s, cx, cy, "N/kN");
    if (!close(a.speed_limit_ms(s), b.speed_limit_ms(s), tolerance_rel))
      return differs("speed limit", s, a.speed_limit_ms(s), b.speed_limit_ms(s), "m/s");
    if (!close(x.tunnel_drag_N_per_kN_kmh2, y.tunnel_drag_N_per_kN_kmh2, tolerance_rel))
      return differs("tunnel drag", s, x.tunnel_drag_N_per_kN_kmh2, y.tunnel_drag_N_per_kN_kmh2,
                     "N/kN/(km/h)^2");
  }
  return "";
}

std::string line_runs_difference(const Line& a, const Line& b, const physics::Train& train,
                                 double tolerance_rel) {
  std::vector<Station> stations = a.stations;
  std::sort(stations.begin(), stations.end(),
            [](const Station& x, const Station& y) { return x.km_post_m < y.km_post_m; });
  for (std::size_t i = 0; i + 1 < stations.size(); ++i) {
    const std::string& from = stations[i].name;
    const std::string& to = stations[i + 1].name;
    std::string why;
    try {
      why = route_difference(build_route(a, from, to, train), build_route(b, from, to, train),
                             tolerance_rel);
    } catch (const std::exception& e) {
      why = e.what();  // e.g. the station is missing from b
    }
    if (!why.empty()) return from + " -> " + to + ": " + why;
  }
  return "";
}

}  // namespace ecorail::data
