// TTOBench journeys: timing points along a track, each with a time window and a speed window
// (any bound may be open: null), read with errors naming the file and JSON path. The first
// point is the departure, the last the arrival; two points at the same position are the
// arrival at and the departure from a stop. Speeds in m/s, times in s from the departure.
// Solving a journey subject to its windows: dp/timing_journey.hpp (`solve --journey`).
#pragma once

#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace ecorail::data {

struct TimingPoint {
  double position_m = 0.0;
  // Open bounds are -inf / +inf.
  double earliest_s = -std::numeric_limits<double>::infinity();
  double latest_s = std::numeric_limits<double>::infinity();
  double min_speed_ms = -std::numeric_limits<double>::infinity();
  double max_speed_ms = std::numeric_limits<double>::infinity();
  bool is_stop() const { return max_speed_ms == 0.0; }
};

struct TtobenchJourney {
  std::string id;
  std::string track_id;  // metadata "associated track"
  std::vector<TimingPoint> points;
};

TtobenchJourney journey_from_ttobench(const std::string& text, const std::string& file);

}  // namespace ecorail::data
