// What the DP minimises besides lambda * time: the traction energy (work at the wheel divided by
// the traction efficiency), or the net energy, which also credits the regenerated braking work
// times the regeneration efficiency.
#pragma once

#include <optional>
#include <string_view>

#include "physics/train.hpp"

namespace ecorail::dp {

enum class Objective { Traction, Net };

// Names to and from text, in one place: "traction", "net".
inline std::string_view objective_name(Objective o) {
  return o == Objective::Net ? "net" : "traction";
}
inline std::optional<Objective> objective_from_name(std::string_view name) {
  if (name == "traction") return Objective::Traction;
  if (name == "net") return Objective::Net;
  return std::nullopt;
}

inline double energy_cost_J(Objective objective, const physics::Train& train,
                            double traction_work_J, double brake_work_J) {
  const double cost = traction_work_J / train.traction_efficiency;
  return objective == Objective::Net ? cost - train.regen_efficiency * brake_work_J : cost;
}

// The same for a train whose efficiencies may be maps over speed and force: then the energy
// drawn and fed back are measured step by step (traction_input_J, regen_J) and the cost is
// read from them; a train with constant efficiencies keeps the formula above, to the bit.
inline double energy_cost_J(Objective objective, const physics::Train& train,
                            double traction_work_J, double brake_work_J, double traction_input_J,
                            double regen_J) {
  if (!train.has_efficiency_maps()) {
    return energy_cost_J(objective, train, traction_work_J, brake_work_J);
  }
  return objective == Objective::Net ? traction_input_J - regen_J : traction_input_J;
}

}  // namespace ecorail::dp
