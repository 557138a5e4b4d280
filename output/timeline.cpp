#include "output/timeline.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace ecorail::output {

void append_section(Timeline& timeline, const physics::SimulationResult& sim,
                    const physics::Route& route, int section) {
  const double t0 = timeline.empty() ? 0.0 : timeline.back().t_s;
  const double s0 = timeline.empty() ? 0.0 : timeline.back().s_m;
  for (std::size_t k = timeline.empty() ? 0 : 1; k < sim.trace.size(); ++k) {
    const physics::TracePoint& p = sim.trace[k];
    const double s = std::min(p.s_m, route.length_m());
    const physics::RouteSegment& seg = route.at(std::max(0.0, s - 1e-9));
    timeline.push_back({t0 + p.t_s, s0 + p.s_m, p.v_ms, p.accel_m_s2, p.force_N,
                        route.km_post_m(p.s_m), seg.gradient_permille, route.speed_limit_ms(s),
                        p.regime, false, section, seg.curve_radius_m});
  }
}

void append_dwell(Timeline& timeline, double dwell_s) {
  if (timeline.empty() || dwell_s <= 0.0) return;
  TimelinePoint p = timeline.back();
  p.t_s += dwell_s;
  p.v_ms = 0.0;
  p.accel_m_s2 = 0.0;
  p.force_N = 0.0;
  p.regime = physics::Regime::Coast;
  p.dwelling = true;
  timeline.push_back(p);
}

Timeline trip_timeline(const physics::Trip& trip) {
  Timeline timeline;
  for (const physics::Trip::Sample& p : trip.samples()) {
    if (p.dwelling) {
      append_dwell(timeline, p.t_s - timeline.back().t_s);
      continue;
    }
    const physics::Route& route = trip.route(p.section);
    const double local = p.s_m - trip.section_start_m(p.section);
    const double s = std::min(local, route.length_m());
    const physics::RouteSegment& seg = route.at(std::max(0.0, s - 1e-9));
    timeline.push_back({p.t_s, p.s_m, p.v_ms, p.accel_m_s2, p.force_N, route.km_post_m(local),
                        seg.gradient_permille, route.speed_limit_ms(s), p.regime, false, p.section,
                        seg.curve_radius_m});
  }
  return timeline;
}

Timeline journey_timeline(const dp::JourneySolution& solution,
                          const std::vector<physics::Route>& routes) {
  if (routes.size() != solution.sections.size()) {
    throw std::invalid_argument("a journey timeline needs one route per section");
  }
  return trip_timeline(dp::journey_trip(solution, routes, 0.0, 1.0));
}

Timeline per_second(const Timeline& timeline) {
  Timeline rows;
  if (timeline.size() < 2) return timeline;
  const double end = timeline.back().t_s;
  std::size_t k = 1;
  for (double t = 1.0;; t += 1.0) {
    const bool last = t >= end - 5e-3;  // a final instant within 5 ms is that second
    const double at = last ? end : t;
    while (k + 1 < timeline.size() && timeline[k].t_s < at) ++k;
    const TimelinePoint& a = timeline[k - 1];
    const TimelinePoint& b = timeline[k];
    const double w = b.t_s > a.t_s ? std::clamp((at - a.t_s) / (b.t_s - a.t_s), 0.0, 1.0) : 1.0;
    TimelinePoint r = b;  // step quantities (force, acceleration, regime) of the step ending at b
    r.t_s = at;
    r.s_m = a.s_m + w * (b.s_m - a.s_m);
    r.v_ms = a.v_ms + w * (b.v_ms - a.v_ms);
    r.km_post_m = a.km_post_m + w * (b.km_post_m - a.km_post_m);
    rows.push_back(r);
    if (last) break;
  }
  return rows;
}

std::string format_hms(double t_s) {
  const double whole = std::round(t_s);
  char buf[48];
  if (std::abs(t_s - whole) < 5e-3) {
    const long s = static_cast<long>(whole);
    std::snprintf(buf, sizeof buf, "%02ld:%02ld:%02ld", s / 3600, (s / 60) % 60, s % 60);
  } else {
    const long s = static_cast<long>(std::floor(t_s));
    std::snprintf(buf, sizeof buf, "%02ld:%02ld:%05.2f", s / 3600, (s / 60) % 60,
                  t_s - static_cast<double>(s - s % 60));
  }
  return buf;
}

}  // namespace ecorail::output
