// StagePrices: a time price per stretch of a section instead of one for the whole of it, and
// speed bands at chosen stages. A journey with timing points prices a second spent before a
// binding window differently from one spent after it (dp/timing_journey.hpp): the backward
// sweep then charges lambda(stage) * dt on each transition out of a stage, and a speed window
// at a timing point makes every node of its stage outside the window infeasible. With one price
// everywhere and no band, a sweep gives bit for bit what the single-price sweep gives.
#pragma once

#include <vector>

namespace ecorail::dp {

// Speeds allowed at one stage of the grid (m/s; open bounds are +-infinity).
struct SpeedBand {
  int stage = 0;
  double min_ms = 0.0;
  double max_ms = 0.0;
};

struct StagePrices {
  // One price (J/s) per transition out of stage i (i = 0 .. stage_count - 2).
  std::vector<double> lambda_J_per_s;
  std::vector<SpeedBand> bands;
};

}  // namespace ecorail::dp
