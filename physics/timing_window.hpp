// A timing point of a journey: a position with a time window and a speed window, any bound
// open (+-inf). The TTOBench journey reader (data/ttobench_journey.hpp) produces them and the
// timing-point journey solver (dp/timing_journey.hpp) meets them; both share this one type, so
// nothing is copied field by field between them. Times in s from the journey's departure,
// speeds in m/s. A speed window [0, 0] is a stop.
#pragma once

#include <limits>

namespace ecorail::physics {

struct TimingWindow {
  double position_m = 0.0;
  double earliest_s = -std::numeric_limits<double>::infinity();
  double latest_s = std::numeric_limits<double>::infinity();
  double min_speed_ms = -std::numeric_limits<double>::infinity();
  double max_speed_ms = std::numeric_limits<double>::infinity();
  bool is_stop() const { return max_speed_ms == 0.0; }
};

}  // namespace ecorail::physics
