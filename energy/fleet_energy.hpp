// The energy account every fleet energy model gives: traction at the wheel, regenerated braking
// energy, and the part of it other trains used at the same moment; the substations supply the
// rest of the traction.
#pragma once

namespace ecorail::energy {

// Energy of a fleet or one train (J).
struct FleetEnergy {
  double traction_J = 0.0;    // at the wheel
  double regen_J = 0.0;       // regenerated (efficiency x braking work)
  double used_regen_J = 0.0;  // regenerated energy other trains took at the same moment
  double substation_J() const { return traction_J - used_regen_J; }
};

}  // namespace ecorail::energy
