// SpeedEnvelope: the highest speed the train may have at each position of a route so that it
// respects every speed limit and the train's maximum speed, and can still brake (at full
// braking) for every lower limit ahead and for the stop at the end. It is sampled on a fine
// uniform position grid by one backward sweep of the full-brake dynamics, and stored as
// specific kinetic energy e = v^2 / 2 (J/kg), in which braking curves are nearly linear. At a
// limit change the stricter limit holds for one sample either side, so the envelope never
// promises a speed the line does not allow.
#pragma once

#include <cmath>
#include <cstddef>
#include <vector>

#include "physics/route.hpp"
#include "physics/train.hpp"

namespace ecorail::physics {

class SpeedEnvelope {
 public:
  SpeedEnvelope() = default;
  SpeedEnvelope(const Train& train, const Route& route, double resolution_m = 0.1);

  // Envelope as specific kinetic energy v^2/2 at s (linear between samples). Inline, as is the
  // static limit: the forward re-simulation asks for both at every 5 cm step.
  double e_at(double s_m) const { return interpolate(e_, h_, s_m); }
  double v_at(double s_m) const;
  // The static limit alone (line limit and train maximum), without braking curves.
  double static_limit_ms(double s_m) const {
    return std::sqrt(2.0 * interpolate(e_static_, h_, s_m));
  }
  double resolution_m() const { return h_; }

 private:
  static double interpolate(const std::vector<double>& samples, double h, double s) {
    if (s <= 0.0) return samples.front();
    const double x = s / h;
    const auto k = static_cast<std::size_t>(x);
    if (k + 1 >= samples.size()) return samples.back();
    const double w = x - static_cast<double>(k);
    return samples[k] + w * (samples[k + 1] - samples[k]);
  }

  double h_ = 0.1;
  double length_ = 0.0;
  std::vector<double> e_;         // envelope samples
  std::vector<double> e_static_;  // static limit samples
};

}  // namespace ecorail::physics
