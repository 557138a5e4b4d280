// TTOBench journeys: timing points along a track, each with a time window and a speed window
// (any bound may be open: null), read with errors naming the file and JSON path. The first
// point is the departure, the last the arrival; two points at the same position are the
// arrival at and the departure from a stop. Speeds in m/s, times in s from the departure.
// Solving a journey subject to its windows: dp/timing_journey.hpp (`solve --journey`).
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "physics/timing_window.hpp"

namespace ecorail::data {

// One timing point (physics/timing_window.hpp, the type the solver takes).
using TimingPoint = physics::TimingWindow;

struct TtobenchJourney {
  std::string id;
  std::string track_id;  // metadata "associated track"
  std::vector<TimingPoint> points;
  // Metadata keys TTOBench does not define (key, JSON text), kept as free text; no solve reads
  // them (data::ttobench_metadata_warnings says so).
  std::vector<std::pair<std::string, std::string>> other_metadata;
};

TtobenchJourney journey_from_ttobench(const std::string& text, const std::string& file);

}  // namespace ecorail::data
