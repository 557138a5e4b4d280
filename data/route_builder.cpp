#include "data/route_builder.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "data/csv_reader.hpp"
#include "data/input_error.hpp"
#include "data/plausibility.hpp"
#include "data/ttobench_route_terms.hpp"
#include "physics/units.hpp"

namespace ecorail::data {

namespace {

// Boundaries closer than this (m) are one boundary; rows must meet within it.
constexpr double kTolerance_m = 1e-6;

std::string station_list(const Line& line) {
  std::string list;
  for (const auto& s : line.stations) list += (list.empty() ? "" : ", ") + s.name;
  return list;
}

const Station& find_or_throw(const Line& line, const std::string& name) {
  if (const Station* s = line.find_station(name)) return *s;
  throw InputError(line.stations_file, 0, "station",
                   "a station of the line, one of " + station_list(line) + "; got '" + name + "'");
}

struct Span {
  double lo = 0.0;    // lower km post of the route
  double hi = 0.0;    // upper km post
  std::string label;  // "between A6 (13594) and A7 (12240)"
};

// The rows of a table that lie on [lo, hi] with positive length, sorted by start, after checking
// that they cover it without gaps.
std::vector<IntervalRow> rows_on_route(const std::vector<IntervalRow>& table,
                                       const std::string& file, const Span& span) {
  std::vector<IntervalRow> rows;
  for (const auto& r : table) {
    if (r.end_km_post_m > span.lo + kTolerance_m && r.start_km_post_m < span.hi - kTolerance_m) {
      rows.push_back(r);
    }
  }
  std::stable_sort(rows.begin(), rows.end(), [](const IntervalRow& a, const IntervalRow& b) {
    return a.start_km_post_m < b.start_km_post_m;
  });
  const std::string what = "rows covering km posts " + format_number(span.lo) + " to " +
                           format_number(span.hi) + " " + span.label;
  if (rows.empty()) throw InputError(file, 0, "", what + "; got none on that stretch");
  if (rows.front().start_km_post_m > span.lo + kTolerance_m) {
    throw InputError(file, rows.front().source_row, "start_km_post_m",
                     what + "; the first row on the stretch starts at " +
                         format_number(rows.front().start_km_post_m));
  }
  for (std::size_t i = 1; i < rows.size(); ++i) {
    if (std::abs(rows[i].start_km_post_m - rows[i - 1].end_km_post_m) > kTolerance_m) {
      throw InputError(file, rows[i].source_row, "start_km_post_m",
                       what + " without gaps or overlaps; the previous row ends at " +
                           format_number(rows[i - 1].end_km_post_m) + ", this one starts at " +
                           format_number(rows[i].start_km_post_m));
    }
  }
  if (rows.back().end_km_post_m < span.hi - kTolerance_m) {
    throw InputError(
        file, rows.back().source_row, "end_km_post_m",
        what + "; the last row on the stretch ends at " + format_number(rows.back().end_km_post_m));
  }
  return rows;
}

// The value of the row holding km post km (strictly inside a piece, so never on a boundary).
double value_at(const std::vector<IntervalRow>& rows, double km) {
  for (const auto& r : rows) {
    if (km >= r.start_km_post_m && km < r.end_km_post_m) return r.value;
  }
  // Within the tolerance of a boundary: the nearest row.
  const IntervalRow* best = &rows.front();
  double best_d = std::numeric_limits<double>::infinity();
  for (const auto& r : rows) {
    const double d = std::max(r.start_km_post_m - km, km - r.end_km_post_m);
    if (d < best_d) {
      best_d = d;
      best = &r;
    }
  }
  return best->value;
}

}  // namespace

physics::Route build_route(const Line& line, const std::string& from, const std::string& to,
                           const physics::Train& train) {
  const Station& a = find_or_throw(line, from);
  const Station& b = find_or_throw(line, to);
  if (from == to) {
    throw InputError(line.stations_file, 0, "station",
                     "two different stations; got '" + from + "' as departure and arrival");
  }
  const double p0 = a.km_post_m;
  const double p1 = b.km_post_m;
  const int dir = p1 < p0 ? -1 : 1;
  const double length = dir * (p1 - p0);
  if (!(length > kTolerance_m)) {
    throw InputError(line.stations_file, b.source_row, "km_post_m",
                     "a km post different from that of " + from + " (" + format_number(p0) +
                         "); got " + format_number(p1) + " for " + to);
  }
  Span span;
  span.lo = std::min(p0, p1);
  span.hi = std::max(p0, p1);
  span.label =
      "between " + from + " (" + format_number(p0) + ") and " + to + " (" + format_number(p1) + ")";
  const auto gradients = rows_on_route(line.gradients, line.gradients_file, span);
  const auto limits = rows_on_route(line.limits, line.limits_file, span);
  const auto curves = rows_on_route(line.curves, line.curves_file, span);

  for (const auto& r : limits) {
    if (!(r.value > 0.0)) {
      throw InputError(line.limits_file, r.source_row, "limit_kmh",
                       "a speed limit above 0 km/h; got " + format_number(r.value));
    }
    // A limit above the train's maximum speed is the track's, not the train's: the train runs
    // at most at its maximum there (capped below; the program says so in its report).
  }
  for (const auto& r : curves) {
    if (r.value < 0.0) {
      throw InputError(line.curves_file, r.source_row, "radius_m",
                       "a radius of at least 0 m (0 = straight); got " + format_number(r.value));
    }
  }

  if (needs_route_terms(line, train)) {  // clothoids, Roeckl, tunnels, train length
    return physics::Route(route_term_segments(line, p0, dir, length, train), p0, dir, from, to);
  }

  // Change points in the travel direction: s = |km - p0|.
  std::vector<double> cuts{0.0, length};
  for (const auto* rows : {&gradients, &limits, &curves}) {
    for (const auto& r : *rows) {
      for (const double km : {r.start_km_post_m, r.end_km_post_m}) {
        const double s = dir * (km - p0);
        if (s > kTolerance_m && s < length - kTolerance_m) cuts.push_back(s);
      }
    }
  }
  std::sort(cuts.begin(), cuts.end());
  std::vector<double> points;
  for (const double s : cuts) {
    if (points.empty() || s - points.back() > kTolerance_m) points.push_back(s);
  }

  std::vector<physics::RouteSegment> segments;
  for (std::size_t i = 0; i + 1 < points.size(); ++i) {
    const double km_mid = p0 + dir * 0.5 * (points[i] + points[i + 1]);
    physics::RouteSegment seg;
    seg.start_m = points[i];
    seg.end_m = points[i + 1];
    // A gradient rising towards increasing km post falls for a train running the other way.
    seg.gradient_permille = dir * value_at(gradients, km_mid) + 0.0;
    seg.curve_radius_m = value_at(curves, km_mid);
    seg.speed_limit_ms = units::kmh_to_ms(value_at(limits, km_mid));
    seg.speed_limit_ms = std::min(seg.speed_limit_ms, train.max_speed_ms);
    if (!segments.empty() && segments.back().gradient_permille == seg.gradient_permille &&
        segments.back().curve_radius_m == seg.curve_radius_m &&
        segments.back().speed_limit_ms == seg.speed_limit_ms) {
      segments.back().end_m = seg.end_m;
    } else {
      segments.push_back(seg);
    }
  }
  physics::Route route(std::move(segments), p0, dir, from, to);
  plausible::check_can_start(train, route, "train '" + train.name + "'");
  return route;
}

std::vector<std::string> stops_between(const Line& line, const std::string& from,
                                       const std::string& to) {
  const Station& a = find_or_throw(line, from);
  const Station& b = find_or_throw(line, to);
  if (&a == &b) {
    throw InputError(line.stations_file, 0, "station",
                     "two different stations; got '" + from + "' twice");
  }
  const auto ia = static_cast<std::size_t>(&a - line.stations.data());
  const auto ib = static_cast<std::size_t>(&b - line.stations.data());
  std::vector<std::string> stops;
  if (ia < ib) {
    for (std::size_t i = ia; i <= ib; ++i) stops.push_back(line.stations[i].name);
  } else {
    for (std::size_t i = ia + 1; i-- > ib;) stops.push_back(line.stations[i].name);
  }
  return stops;
}

std::vector<physics::Route> build_routes(const Line& line, const std::vector<std::string>& stops,
                                         const physics::Train& train) {
  if (stops.size() < 2) {
    throw InputError(line.stations_file, 0, "station", "at least two stops for a run");
  }
  std::vector<physics::Route> routes;
  for (std::size_t i = 0; i + 1 < stops.size(); ++i) {
    routes.push_back(build_route(line, stops[i], stops[i + 1], train));
  }
  return routes;
}

}  // namespace ecorail::data
