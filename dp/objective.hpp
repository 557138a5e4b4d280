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

}  // namespace ecorail::dp
