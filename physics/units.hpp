// Unit conversions at the edges of the engine. Inside, everything is SI (m, s, m/s, N, J);
// files and reports use km/h, kN, kJ and per mille. Keeping the factors in one place means a
// unit slip shows up as a wrong name, not a wrong number.
#pragma once

namespace ecorail::units {

inline constexpr double kKmhPerMs = 3.6;

constexpr double kmh_to_ms(double v_kmh) {
  return v_kmh / kKmhPerMs;
}
constexpr double ms_to_kmh(double v_ms) {
  return v_ms * kKmhPerMs;
}
constexpr double kN_to_N(double f_kN) {
  return f_kN * 1000.0;
}
constexpr double N_to_kN(double f_N) {
  return f_N / 1000.0;
}
constexpr double J_to_kJ(double e_J) {
  return e_J / 1000.0;
}
constexpr double kJ_to_J(double e_kJ) {
  return e_kJ * 1000.0;
}
constexpr double t_to_kg(double m_t) {
  return m_t * 1000.0;
}
constexpr double kW_to_W(double p_kW) {
  return p_kW * 1000.0;
}

}  // namespace ecorail::units
