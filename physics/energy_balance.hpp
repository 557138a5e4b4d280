// Energy balance of a re-simulated run, the last check before a result is reported: the work
// of the applied force (traction - braking) must equal the work done against resistance
// (Davis, gradient, curve, tunnel) plus the change of kinetic energy, and the dissipative part
// (Davis and tunnel drag) can only take energy out. Input that slipped past validation (a
// negative Davis coefficient once "regenerated" 77 times the traction energy and was reported
// as converged) then cannot come out as a success. The resistance is integrated over the trace
// independently of the simulator's ledger, with the force law of Motion::resistance_N.
#pragma once

#include "physics/motion.hpp"
#include "physics/simulator.hpp"

namespace ecorail::physics {

struct EnergyBalance {
  double traction_work_J = 0.0;    // from the ledger
  double brake_work_J = 0.0;       // from the ledger
  double resistance_work_J = 0.0;  // all resistance along the trace (gradient included)
  double dissipation_J = 0.0;      // Davis and tunnel drag only: never negative in a real train
  double kinetic_change_J = 0.0;   // effective mass, end minus start
  double residual_J = 0.0;         // traction - brake - resistance - kinetic change
  double tolerance_J = 0.0;        // 0.1 % of the energies moved, at least 1 kJ
  bool closes() const {
    return std::abs(residual_J) <= tolerance_J && dissipation_J >= -tolerance_J;
  }
};

EnergyBalance energy_balance(const Motion& motion, const SimulationResult& sim);

}  // namespace ecorail::physics
