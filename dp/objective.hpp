// What the DP minimises besides lambda * time: the traction energy (work at the wheel divided by
// the traction efficiency), or the net energy, which also credits the regenerated braking work
// times the regeneration efficiency.
#pragma once

#include "physics/train.hpp"

namespace ecorail::dp {

enum class Objective { Traction, Net };

inline double energy_cost_J(Objective objective, const physics::Train& train,
                            double traction_work_J, double brake_work_J) {
  const double cost = traction_work_J / train.traction_efficiency;
  return objective == Objective::Net ? cost - train.regen_efficiency * brake_work_J : cost;
}

}  // namespace ecorail::dp
