// The equation of motion the fits explain a log with, written once for doubles and for Ceres'
// automatic-differentiation Jets. It is the engine's single-mass-point model (physics/train.hpp)
// with the logged force as input instead of a control:
//   M (1 + rho) dv/dt = k_F u_traction - u_braking - (w0(v) + s_g i + 600/R) M g / 1000,
// w0 = A + B v + C v^2 in N/kN with v in km/h, s_g the gradient scale, k_F the traction scale,
// and the base train's acceleration limits applied as the engine applies them (a log that
// records the envelope force while the limit holds the train at 1 m/s^2 is read correctly).
// integrate_interval advances the speed between two rows with classic Runge-Kutta in time,
// force and track resistance interpolated linearly between the rows: the output-error
// formulation's simulator, checked against physics::simulate in the tests.
#pragma once

#include <cmath>

#include "fitting/log_prep.hpp"
#include "fitting/parameters.hpp"

namespace ecorail::fitting {

struct ModelConstants {
  double gravity_m_s2 = 9.8;
  double max_accel_m_s2 = 1.0;
  double max_decel_m_s2 = 1.0;
  bool apply_accel_limits = true;
  double max_substep_s = 1.0;
};

template <typename T>
T model_accel(const T* p, const ModelConstants& k, const T& v_ms, double traction_N,
              double braking_N, double gradient_permille, double curve_N_per_kN) {
  const T v_kmh = v_ms * 3.6;
  const T w = p[kDavisA] + v_kmh * (p[kDavisB] + v_kmh * p[kDavisC]) +
              p[kGradientScale] * gradient_permille + curve_N_per_kN;
  const T inertia = T(1.0) + p[kRotatingMassFactor];
  T a = (p[kTractionScale] * traction_N - braking_N) / (p[kMassT] * 1000.0 * inertia) -
        (k.gravity_m_s2 / 1000.0) * w / inertia;
  if (k.apply_accel_limits) {
    if (traction_N > 0.0 && a > k.max_accel_m_s2) a = T(k.max_accel_m_s2);
    if (braking_N > 0.0 && a < -k.max_decel_m_s2) a = T(-k.max_decel_m_s2);
  }
  return a;
}

template <typename T>
T row_accel(const T* p, const ModelConstants& k, const PreparedRow& r) {
  return model_accel(p, k, T(r.speed_ms), r.traction_N, r.braking_N, r.gradient_permille,
                     r.curve_N_per_kN);
}

// Speed at row b's time after starting from v at row a's time.
template <typename T>
T integrate_interval(const T* p, const ModelConstants& k, T v, const PreparedRow& a,
                     const PreparedRow& b) {
  const double dt = b.time_s - a.time_s;
  const int n = std::max(1, static_cast<int>(std::ceil(dt / k.max_substep_s - 1e-9)));
  const double h = dt / n;
  auto f = [&](double frac, const T& vv) {
    const double trac = a.traction_N + frac * (b.traction_N - a.traction_N);
    const double brake = a.braking_N + frac * (b.braking_N - a.braking_N);
    const double grade = a.gradient_permille + frac * (b.gradient_permille - a.gradient_permille);
    const double curve = a.curve_N_per_kN + frac * (b.curve_N_per_kN - a.curve_N_per_kN);
    return model_accel(p, k, vv, trac, brake, grade, curve);
  };
  for (int i = 0; i < n; ++i) {
    const double f0 = static_cast<double>(i) / n;
    const double fm = (i + 0.5) / n;
    const double f1 = static_cast<double>(i + 1) / n;
    const T k1 = f(f0, v);
    const T k2 = f(fm, v + 0.5 * h * k1);
    const T k3 = f(fm, v + 0.5 * h * k2);
    const T k4 = f(f1, v + h * k3);
    v = v + (h / 6.0) * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
    if (v < 0.0) v = T(0.0);
  }
  return v;
}

}  // namespace ecorail::fitting
