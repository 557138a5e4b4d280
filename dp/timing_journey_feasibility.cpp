#include "dp/timing_journey_feasibility.hpp"

#include <algorithm>
#include <string>

#include "dp/text_format.hpp"
#include "dp/timing_journey_part.hpp"
#include "physics/speed_envelope.hpp"
#include "physics/units.hpp"

namespace ecorail::dp::timing {

bool pins_the_state(const TimingWindow& w) {
  return !w.is_stop() && finite(w.earliest_s) && w.earliest_s == w.latest_s &&
         finite(w.min_speed_ms) && w.min_speed_ms == w.max_speed_ms && w.min_speed_ms > 0.0;
}

std::vector<PartBounds> split_into_parts(const std::vector<TimingWindow>& w) {
  std::vector<PartBounds> parts;
  int first = 0;
  const int n = static_cast<int>(w.size());
  for (int i = 1; i < n; ++i) {
    if (!(w[i].is_stop() || pins_the_state(w[i]) || i == n - 1)) continue;
    parts.push_back({first, i});
    // Two points at one position: arrival at and departure from the stop.
    if (i + 1 < n && w[i + 1].position_m == w[i].position_m) ++i;
    first = i;
  }
  return parts;
}

void check_structure(const std::vector<TimingWindow>& w, double track_length_m) {
  const int n = static_cast<int>(w.size());
  if (n < 2) throw WindowInfeasibleError(0, "a journey needs at least two timing points");
  for (int i = 0; i < n; ++i) {
    const TimingWindow& p = w[i];
    if (!(p.position_m >= 0.0 && p.position_m <= track_length_m + 1e-6)) {
      throw WindowInfeasibleError(i, format_text("%s lies outside the track (0 to %.1f m)",
                                                 point_name(i, p).c_str(), track_length_m));
    }
    if (p.earliest_s > p.latest_s || p.min_speed_ms > p.max_speed_ms) {
      throw WindowInfeasibleError(i, point_name(i, p) + " has a lower bound above its upper bound");
    }
    if (i > 0) {
      const TimingWindow& q = w[i - 1];
      if (p.position_m < q.position_m) {
        throw WindowInfeasibleError(i, point_name(i, p) + " lies before the point before it");
      }
      if (p.position_m == q.position_m && !(p.is_stop() && q.is_stop())) {
        throw WindowInfeasibleError(
            i, point_name(i, p) +
                   " shares its position with the point before it, but only a stop (speed "
                   "window [0, 0]) may have two points (arrival and departure)");
      }
      if (p.position_m == q.position_m && i >= 2 && w[i - 2].position_m == p.position_m) {
        throw WindowInfeasibleError(i, point_name(i, p) + ": a stop has at most two points");
      }
    }
  }
  if (w.back().position_m <= w.front().position_m) {
    throw WindowInfeasibleError(n - 1, "the last timing point must lie after the first");
  }
  if (!finite(w.back().latest_s)) {
    throw WindowInfeasibleError(
        n - 1, point_name(n - 1, w.back()) + " needs a latest time (the arrival's)");
  }
}

// The route whose speed envelope a part that ends moving uses: the part, then a level, straight
// stretch whose limit is the end window's top speed (the line's limit at the end when that is
// lower or the window has none), long enough that the envelope does not brake to rest before
// its end. The envelope at the end point is then the lower of the window's top speed and the
// line's limit there, and the grid's last stage has every speed up to it. Nothing beyond the
// last timing point is braked for: the journey ends there.
physics::Route runoff_route(const physics::Train& train, const physics::Route& part, double top_ms,
                            double resolution_m) {
  const double length = part.length_m();
  physics::RouteSegment extra = part.segments().back();
  extra.start_m = length;
  extra.gradient_permille = 0.0;
  extra.curve_radius_m = 0.0;
  extra.curve_N_per_kN = -1.0;
  extra.tunnel_drag_N_per_kN_kmh2 = 0.0;
  if (finite(top_ms)) extra.speed_limit_ms = std::min(extra.speed_limit_ms, top_ms);
  const int direction = part.km_post_m(1.0) >= part.km_post_m(0.0) ? 1 : -1;
  for (double runoff_m = 500.0;; runoff_m *= 2.0) {
    std::vector<physics::RouteSegment> segs = part.segments();
    extra.end_m = length + runoff_m;
    segs.push_back(extra);
    physics::Route route(std::move(segs), part.km_post_m(0.0), direction, part.from_name(),
                         part.to_name());
    const physics::SpeedEnvelope envelope(train, route, resolution_m);
    if (envelope.v_at(length) >= envelope.static_limit_ms(length) - 1e-6 || runoff_m > 2e5) {
      return route;
    }
  }
}

FlatOutModel::FlatOutModel(const physics::Train& train, const physics::Route& route,
                           const physics::Route& envelope_route, const EngineOptions& options)
    : train_(train),
      route_(route),
      envelope_(train_, envelope_route, options.envelope_resolution_m),
      motion_(train_, route_, envelope_),
      step_m_(options.resim_step_m) {}

physics::SimulationResult FlatOutModel::min_time_run(const StartState& start) const {
  physics::SimulationOptions opt;
  opt.step_m = step_m_;
  opt.start_position_m = start.position_m;
  opt.start_speed_ms = start.speed_ms;
  return physics::simulate(motion_, {{start.position_m, physics::Control::MaxTraction}}, opt);
}

std::vector<double> earliest_times(const std::vector<TimingWindow>& windows,
                                   const std::vector<PartBounds>& bounds,
                                   const std::vector<std::unique_ptr<FlatOutModel>>& engines,
                                   const std::vector<StartState>& starts, double departure0_s,
                                   double tol_t, double tol_v) {
  const int n = static_cast<int>(windows.size());
  // The proof of infeasibility: the earliest time each point can be reached, from flat-out
  // runs. Leaving point i at the highest speed its window and the line allow and running flat
  // out is the fastest any run can cover the stretch to point i + 1 (no run is faster than the
  // envelope-following flat-out run from the highest speed), so earliest[i + 1] >= earliest[i]
  // + that time is a lower bound; a point whose lower bound exceeds its latest time is proved
  // infeasible. cause[i]: the point whose earliest bound the chain starts from.
  std::vector<double> earliest(n), min_leg_s(n, 0.0);
  std::vector<int> cause(n);
  earliest[0] = departure0_s;
  cause[0] = 0;
  for (std::size_t j = 0; j < bounds.size(); ++j) {
    const FlatOutModel& engine = *engines[j];
    const double origin = windows[bounds[j].first].position_m;
    for (int i = bounds[j].first; i < bounds[j].last; ++i) {
      const TimingWindow& w = windows[i];
      const double s = w.position_m - origin;
      double v = i == bounds[j].first ? starts[j].speed_ms
                                      : std::min(engine.envelope().v_at(s), w.max_speed_ms);
      v = std::max(0.0, v);
      const physics::SimulationResult flat = engine.min_time_run({s, v});
      const Passing at_next = passing_at(flat.trace, windows[i + 1].position_m - origin);
      min_leg_s[i + 1] = finite(at_next.t_s) ? at_next.t_s : kInf;
      if (finite(at_next.v_ms) && windows[i + 1].min_speed_ms > at_next.v_ms + tol_v) {
        throw WindowInfeasibleError(
            i + 1, format_text("%s: min speed %.2f km/h cannot be met: the train reaches at "
                               "most %.2f km/h there",
                               point_name(i + 1, windows[i + 1]).c_str(),
                               units::ms_to_kmh(windows[i + 1].min_speed_ms),
                               units::ms_to_kmh(at_next.v_ms)));
      }
      double e = earliest[i] + min_leg_s[i + 1];
      cause[i + 1] = cause[i];
      if (windows[i + 1].earliest_s > e) e = windows[i + 1].earliest_s, cause[i + 1] = i + 1;
      earliest[i + 1] = e;
      if (e > windows[i + 1].latest_s + tol_t) {
        const int c = cause[i];
        std::string from =
            c == 0 ? format_text("departing at %.1f s", earliest[0])
                   : format_text("%s no earlier than %.1f s (its window)",
                                 point_name(c, windows[c]).c_str(), windows[c].earliest_s);
        throw WindowInfeasibleError(
            i + 1,
            format_text("%s: latest %.1f s cannot be met: %s, the train needs at least %.1f s "
                        "from %.1f m to %.1f m (flat out), so it arrives no earlier than %.1f s",
                        point_name(i + 1, windows[i + 1]).c_str(), windows[i + 1].latest_s,
                        from.c_str(), e - earliest[c], windows[c].position_m,
                        windows[i + 1].position_m, e));
      }
    }
    // The next part departs from the same stop (its second point, if it has one).
    if (j + 1 < bounds.size() && bounds[j + 1].first != bounds[j].last) {
      const int dep = bounds[j + 1].first;
      double e = earliest[bounds[j].last];
      cause[dep] = cause[bounds[j].last];
      if (windows[dep].earliest_s > e) e = windows[dep].earliest_s, cause[dep] = dep;
      earliest[dep] = e;
      if (e > windows[dep].latest_s + tol_t) {
        throw WindowInfeasibleError(
            dep, format_text("%s: latest departure %.1f s cannot be met: the train arrives "
                             "there no earlier than %.1f s",
                             point_name(dep, windows[dep]).c_str(), windows[dep].latest_s, e));
      }
    }
  }

  return earliest;
}

}  // namespace ecorail::dp::timing
