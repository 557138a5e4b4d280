#include "physics/coasting.hpp"

#include <cmath>
#include <stdexcept>

#include "physics/units.hpp"

namespace ecorail::physics {

CoastingCurve::CoastingCurve(const Train& train, double track_N_per_kN) {
  const double g = train.gravity_m_s2 / 1000.0;  // N/kN -> m/s^2 per unit of specific resistance
  const double kmh = units::kKmhPerMs;
  k_ = 1.0 + train.rotating_mass_factor;
  alpha_ = g * (train.davis.A + track_N_per_kN);
  beta_ = g * train.davis.B * kmh;
  gamma_ = g * train.davis.C * kmh * kmh;
  if (gamma_ < 0.0 || beta_ < 0.0) throw std::invalid_argument("Davis B and C must be >= 0");
  if (alpha_ < 0.0) {
    // Positive root of Q: the balancing speed of the descent.
    balancing_ms_ = gamma_ > 0.0
                        ? (-beta_ + std::sqrt(beta_ * beta_ - 4.0 * alpha_ * gamma_)) / (2 * gamma_)
                        : (beta_ > 0.0 ? -alpha_ / beta_ : 0.0);
  }
}

double CoastingCurve::deceleration(double v) const {
  return (alpha_ + v * (beta_ + v * gamma_)) / k_;
}

double CoastingCurve::H(double v) const {
  if (gamma_ > 0.0) {
    const double d = beta_ * beta_ - 4.0 * alpha_ * gamma_;
    const double x = 2.0 * gamma_ * v + beta_;
    if (d < 0.0) {
      const double r = std::sqrt(-d);
      return 2.0 / r * std::atan(x / r);
    }
    if (d > 0.0) {
      const double r = std::sqrt(d);
      return std::log(std::abs((x - r) / (x + r))) / r;
    }
    return -2.0 / x;
  }
  if (beta_ > 0.0) return std::log(std::abs(beta_ * v + alpha_)) / beta_;
  return v / alpha_;
}

double CoastingCurve::G(double v) const {
  if (gamma_ > 0.0) {
    const double q = alpha_ + v * (beta_ + v * gamma_);
    return std::log(std::abs(q)) / (2.0 * gamma_) - beta_ / (2.0 * gamma_) * H(v);
  }
  if (beta_ > 0.0) {
    return v / beta_ - alpha_ / (beta_ * beta_) * std::log(std::abs(beta_ * v + alpha_));
  }
  return v * v / (2.0 * alpha_);
}

double CoastingCurve::distance_m(double v0, double v1) const {
  return k_ * (G(v0) - G(v1));
}

double CoastingCurve::time_s(double v0, double v1) const {
  return k_ * (H(v0) - H(v1));
}

double CoastingCurve::speed_after_m(double v0, double s_m) const {
  // The coast tends to the balancing speed (if v0 is on its far side or it exists) or to rest.
  const double limit = has_balancing_speed() ? balancing_ms_ : 0.0;
  if (v0 == limit || s_m <= 0.0) return v0;
  if (limit == 0.0 && s_m >= distance_m(v0, 0.0)) return 0.0;
  // distance_m(v0, v) grows monotonically as v moves from v0 towards the limit: bisect.
  double lo = v0, hi = limit;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    if (mid == lo || mid == hi) break;
    (distance_m(v0, mid) < s_m ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

double CoastingCurve::time_after_m(double v0, double s_m) const {
  return time_s(v0, speed_after_m(v0, s_m));
}

}  // namespace ecorail::physics
