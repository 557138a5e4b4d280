// Timeline: a run laid out for reporting. Each point carries time and distance from the start
// of the run (a journey's sections and dwells follow one another), the state, the force, the
// kilometre post and the track data at that point. per_second() samples a timeline at every
// whole second, as in the published tables, plus the final instant.
#pragma once

#include <string>
#include <vector>

#include "dp/journey.hpp"
#include "physics/route.hpp"
#include "physics/simulator.hpp"
#include "physics/trip.hpp"

namespace ecorail::output {

struct TimelinePoint {
  double t_s = 0.0;
  double s_m = 0.0;  // distance from the start of the run
  double v_ms = 0.0;
  double accel_m_s2 = 0.0;
  double force_N = 0.0;  // traction positive, braking negative
  double km_post_m = 0.0;
  double gradient_permille = 0.0;  // in the travel direction
  double speed_limit_ms = 0.0;
  physics::Regime regime = physics::Regime::Coast;
  bool dwelling = false;
  int section = 0;
  double curve_radius_m = 0.0;  // 0 = straight track
};

using Timeline = std::vector<TimelinePoint>;

// Appends a re-simulated section run; time and distance continue from the timeline's end.
void append_section(Timeline& timeline, const physics::SimulationResult& sim,
                    const physics::Route& route, int section);
// Appends a dwell at the last point of the timeline.
void append_dwell(Timeline& timeline, double dwell_s);
// A trip laid out for reporting: its samples on the trip's own time axis (0 at departure), with
// the kilometre post and track data of each point. The per-second tables of sections and
// journeys are read from here.
Timeline trip_timeline(const physics::Trip& trip);
// A journey laid out for reporting: each section's re-simulated run, with its dwell after it
// (routes: the journey's, one per section); the timeline of dp::journey_trip.
Timeline journey_timeline(const dp::JourneySolution& solution,
                          const std::vector<physics::Route>& routes);
// Samples at t = 1, 2, ... s and at the final instant, interpolating linearly in time.
Timeline per_second(const Timeline& timeline);

// "hh:mm:ss", with hundredths when t is not a whole second.
std::string format_hms(double t_s);

}  // namespace ecorail::output
