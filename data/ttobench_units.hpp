// The conversions between TTOBench's absolute resistance forces and ecorail's specific Davis
// coefficients (N/kN, v in km/h), in one place so that the reader and the writer invert each
// other exactly (the writer searches the ulps around the plain inverse; see ttobench_writer).
#pragma once

#include "physics/train.hpp"
#include "physics/units.hpp"

namespace ecorail::data::ttobench {

// TTOBench trains are read with standard gravity (TTOBench states no value).
inline constexpr double kGravity_m_s2 = 9.81;

// A force (or force coefficient) in N for the train's weight -> N/kN.
inline double force_to_specific(double force_N, const physics::Train& t) {
  return force_N * 1000.0 / (t.mass_kg * t.gravity_m_s2);
}
inline double specific_to_force(double specific, const physics::Train& t) {
  return specific * t.mass_kg * t.gravity_m_s2 / 1000.0;
}
inline double kmh_to_ms(double v_kmh) {
  return units::kmh_to_ms(v_kmh);
}

}  // namespace ecorail::data::ttobench
