// Shared helpers of the fitting tests: the reference train, a "truth" train that differs from it
// in every calibrated parameter, and paths to the published tables.
#pragma once

#include <string>

#include "data/train_io.hpp"
#include "physics/train.hpp"

namespace ecorail::fitting::test {

inline physics::Train reference_train() {
  return data::default_train();
}

// Davis coefficients and mass factor moved well away from the reference, so a calibration that
// starts from the reference has real work to do.
inline physics::Train truth_train() {
  physics::Train t = data::default_train();
  t.davis.A = 2.6;
  t.davis.B = 0.045;
  t.davis.C = 0.0021;
  t.rotating_mass_factor = 0.08;
  return t;
}

inline std::string published_table(const std::string& name) {
  return std::string(ECORAIL_SOURCE_DIR) + "/data/contest/" + name;
}

}  // namespace ecorail::fitting::test
