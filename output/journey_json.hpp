// JSON report of a journey (several sections with dwells): the totals under the same keys as a
// single-section solve, then each section's time, energy, marginal energy per second and
// regimes, and the equal-lambda check of the optimal split.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "dp/journey.hpp"

namespace ecorail::output {

struct JourneyLabels {
  std::vector<std::string> stops;  // from, intermediate stops..., to
  std::string split;               // "optimal" or "proportional"
  double ds_m = 0.0, dv_kmh = 0.0;
  int threads = 1;
};

nlohmann::json journey_json(const dp::JourneySolution& solution, const JourneyLabels& labels);

}  // namespace ecorail::output
