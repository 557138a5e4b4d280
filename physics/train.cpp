#include "physics/train.hpp"

#include <algorithm>

#include "physics/units.hpp"

namespace ecorail::physics {

double Train::davis_N_per_kN(double v_ms) const {
  const double v = units::ms_to_kmh(v_ms);
  return davis.A + v * (davis.B + v * davis.C);
}

double Train::max_traction_N(double v_ms, double resistance_N) const {
  const double limit = effective_mass_kg() * max_accel_m_s2 + resistance_N;
  return std::max(0.0, std::min(traction.force_N(v_ms), limit));
}

double Train::max_brake_N(double v_ms, double resistance_N) const {
  // dv/dt = (-b - W) / M_eff >= -max_decel  <=>  b <= M_eff max_decel - W
  const double limit = effective_mass_kg() * max_decel_m_s2 - resistance_N;
  return std::max(0.0, std::min(braking.force_N(v_ms) + pneumatic_brake_N, limit));
}

}  // namespace ecorail::physics
