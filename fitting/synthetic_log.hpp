// Synthetic per-second logs made by the engine's own integrator (physics::simulate) from a
// known train, for testing the calibration and for benchmarks. A log is a sequence of station
// runs on random gradient profiles, each driven by a feedback law that alternates full traction
// to a random speed, coasting down to a lower one and now and then full braking, with dwells at
// standstill between runs. Rows are sampled every second from the fine trace; speeds get
// Gaussian noise and a chosen fraction of rows is corrupted by a gross speed error, whose rows
// are returned so tests can check which rows a fit discounts.
#pragma once

#include <cstdint>
#include <vector>

#include "fitting/log_reader.hpp"
#include "physics/train.hpp"

namespace ecorail::fitting {

struct SyntheticLogOptions {
  int rows = 2000;
  double sample_s = 1.0;
  double speed_noise_kmh = 0.2;   // standard deviation on moving rows
  double corrupt_fraction = 0.0;  // share of rows with a gross speed error
  double corrupt_min_kmh = 2.0;   // size of that error, uniform in [min, max], random sign
  double corrupt_max_kmh = 8.0;
  double max_gradient_permille = 6.0;
  double dwell_s = 20.0;
  double step_m = 0.25;  // simulator step
  std::uint64_t seed = 1;
};

struct SyntheticLog {
  Log log;                          // plain format with position, gradient and both forces
  std::vector<int> corrupted_rows;  // source rows (1-based file lines) with a gross error
};

SyntheticLog make_synthetic_log(const physics::Train& truth, const SyntheticLogOptions& options);

}  // namespace ecorail::fitting
