// The timing-journey tests' tracks and grid: a level track with one rise in its middle under an
// 80 km/h limit, and the coarse grid (10 m x 0.5 km/h) that keeps each journey to a second; the
// open bound, a stop's window, and how exactly a zero-width window is met (1 ms, 0.01 km/h).
#pragma once

#include <limits>
#include <string>
#include <vector>

#include "dp/timing_journey.hpp"
#include "physics/route.hpp"
#include "physics/units.hpp"

namespace ecorail::dp::timing_test {

inline constexpr double kOpen = std::numeric_limits<double>::infinity();
inline constexpr double kExactTime_s = 1e-3;
inline constexpr double kExactSpeed_ms = 0.01 / 3.6;

// At rest at position s, some time in [earliest, latest].
inline TimingWindow stop_at(double s, double earliest, double latest) {
  return {s, earliest, latest, 0.0, 0.0};
}

// Level from 0 to rise_from_m, rise_permille up to rise_to_m, level again to length_m.
inline physics::Route rise_track(double rise_from_m, double rise_to_m, double length_m,
                                 double rise_permille, const std::string& from,
                                 const std::string& to) {
  std::vector<physics::RouteSegment> segs(3);
  const double ends[] = {rise_from_m, rise_to_m, length_m};
  double start = 0.0;
  for (int i = 0; i < 3; ++i) {
    segs[i].start_m = start;
    segs[i].end_m = ends[i];
    segs[i].gradient_permille = i == 1 ? rise_permille : 0.0;
    segs[i].speed_limit_ms = units::kmh_to_ms(80.0);
    start = ends[i];
  }
  return physics::Route(segs, 0.0, 1, from, to);
}

inline TimingJourneyOptions coarse_timing() {
  TimingJourneyOptions o;
  o.engine.grid.ds_m = 10.0;
  o.engine.grid.dv_kmh = 0.5;
  o.engine.grid.substep_m = 5.0;
  return o;
}

}  // namespace ecorail::dp::timing_test
