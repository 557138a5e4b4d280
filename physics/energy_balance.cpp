#include "physics/energy_balance.hpp"

#include <algorithm>
#include <cmath>

namespace ecorail::physics {

EnergyBalance energy_balance(const Motion& motion, const SimulationResult& sim) {
  EnergyBalance b;
  b.traction_work_J = sim.energy.traction_work_J;
  b.brake_work_J = sim.energy.brake_work_J;
  const Train& train = motion.train();
  const Route& route = motion.route();
  const auto& trace = sim.trace;
  for (std::size_t k = 1; k < trace.size(); ++k) {
    const double ds = trace[k].s_m - trace[k - 1].s_m;
    if (!(ds > 0.0)) continue;
    // Midpoint rule on each step (5 cm in a re-simulation): speed as the mean of the ends.
    const double v = 0.5 * (trace[k].v_ms + trace[k - 1].v_ms);
    const double s = std::min(0.5 * (trace[k].s_m + trace[k - 1].s_m), route.length_m());
    const RouteSegment& seg = route.at(std::max(0.0, s));
    const double w_N = motion.resistance_N(v, seg);
    b.resistance_work_J += w_N * ds;
    b.dissipation_J += (w_N - train.specific_to_N(seg.track_N_per_kN())) * ds;
  }
  if (!trace.empty()) {
    const double v0 = trace.front().v_ms;
    const double v1 = trace.back().v_ms;
    b.kinetic_change_J = 0.5 * train.effective_mass_kg() * (v1 * v1 - v0 * v0);
  }
  b.residual_J = b.traction_work_J - b.brake_work_J - b.resistance_work_J - b.kinetic_change_J;
  const double moved = b.traction_work_J + b.brake_work_J + std::abs(b.resistance_work_J) +
                       std::abs(b.kinetic_change_J);
  b.tolerance_J = std::max(1e3, 1e-3 * moved);
  return b;
}

}  // namespace ecorail::physics
