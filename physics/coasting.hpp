// Closed-form coasting: speed-distance and time-distance of a train with no applied force on a
// constant gradient and curve, under quadratic (Davis) resistance. With k = 1 + rho and
//   dv/dt = -Q(v) / k,   Q(v) = gamma v^2 + beta v + alpha   (v in m/s, per unit mass),
// distance and time between two speeds are k [G(v0) - G(v1)] and k [H(v0) - H(v1)], with
// H = integral dv / Q and G = integral v dv / Q in closed form (atan when Q has no real root,
// logarithms when it has). On a steep enough descent alpha < 0 and Q has a positive root, the
// balancing speed: a coasting train converges to it from either side and never reaches it.
// Used as an independent check of the integrator and of the DP's coasting arcs.
#pragma once

#include "physics/train.hpp"

namespace ecorail::physics {

class CoastingCurve {
 public:
  CoastingCurve(const Train& train, double track_N_per_kN);

  // Distance (m) and time (s) to coast from v0 to v1 (both m/s); v1 must lie between v0 and the
  // speed the coast tends to (0, or the balancing speed).
  double distance_m(double v0, double v1) const;
  double time_s(double v0, double v1) const;
  // Speed and elapsed time after coasting a distance s from v0 (0 once the train has stopped).
  double speed_after_m(double v0, double s_m) const;
  double time_after_m(double v0, double s_m) const;
  // Net deceleration per unit mass at v (m/s^2, positive = slowing down).
  double deceleration(double v) const;
  bool has_balancing_speed() const { return balancing_ms_ > 0.0; }
  double balancing_speed_ms() const { return balancing_ms_; }

 private:
  double H(double v) const;
  double G(double v) const;

  double k_ = 1.0;
  double alpha_ = 0.0, beta_ = 0.0, gamma_ = 0.0;
  double balancing_ms_ = 0.0;
};

}  // namespace ecorail::physics
