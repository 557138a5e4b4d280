// Speed-distance profiles of a simulated service: each train's run sampled on a time step with,
// at every sample, the separation cap behind the train ahead (sqrt(2 L b), L from the leader's
// actual run; none for the first train or once the leader has left the line) and the line's
// speed limit. They are what a planner checks the runs against; output/service_profiles.* writes
// them (long-format CSV for all trains, SVG for one).
#pragma once

#include <limits>
#include <vector>

#include "physics/trip.hpp"
#include "service/separation.hpp"

namespace ecorail::service {

struct ProfilePoint {
  double clock_s = 0.0;
  double position_m = 0.0;  // along the run
  double speed_ms = 0.0;
  double cap_ms = std::numeric_limits<double>::infinity();  // separation cap (inf: none)
  double limit_ms = 0.0;                                    // line speed limit here
};

// Train k of trips (on the clock, in departure order), every step_s from its departure and at
// its arrival; the cap from trips[k - 1].
std::vector<ProfilePoint> speed_profile(const std::vector<physics::Trip>& trips, std::size_t k,
                                        double braking_m_s2, const SeparationOptions& options,
                                        double step_s);

}  // namespace ecorail::service
