#include "physics/speed_envelope.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace ecorail::physics {

namespace {

// The braking curves use this fraction of the full braking force, so a train on a curve can
// always follow it despite the small difference between the envelope's sampling and the
// integrator's steps (it costs under 0.01 % of a stop's braking time).
constexpr double kBrakeMargin = 1.0 - 2e-4;

// At most this many samples (16 bytes each): 1 cm over 1000 km.
constexpr double kMaxSamples = 1e8;

// de/ds of full braking, integrated backwards (so the sign is positive): (B + W) / M_eff.
double backward_brake_slope(const Train& train, double e, double track_N_per_kN) {
  const double v = e > 0.0 ? std::sqrt(2.0 * e) : 0.0;
  const double w = train.resistance_N(v, track_N_per_kN);
  return (kBrakeMargin * train.max_brake_N(v, w) + w) / train.effective_mass_kg();
}

}  // namespace

SpeedEnvelope::SpeedEnvelope(const Train& train, const Route& route, double resolution_m) {
  length_ = route.length_m();
  // Checked before the cast: a tiny or subnormal resolution gives a count no integer holds
  // (undefined behaviour) or one no memory holds.
  const double wanted = std::ceil(length_ / resolution_m);
  if (!(resolution_m > 0.0) || !(wanted <= kMaxSamples)) {
    throw std::invalid_argument("speed envelope: a resolution of " + std::to_string(resolution_m) +
                                " m over " + std::to_string(length_) + " m needs more than " +
                                std::to_string(static_cast<long long>(kMaxSamples)) + " samples");
  }
  const auto samples = static_cast<std::size_t>(std::max(1.0, wanted));
  h_ = length_ / static_cast<double>(samples);
  e_static_.assign(samples + 1, 0.0);
  // Static limit: the strictest limit of any segment within one sample of the position.
  for (std::size_t k = 0; k <= samples; ++k) {
    const double s = static_cast<double>(k) * h_;
    const std::size_t lo = route.index_at(std::max(0.0, s - h_));
    const std::size_t hi = route.index_at(std::min(length_, s + h_));
    double v = train.max_speed_ms;
    for (std::size_t i = lo; i <= hi; ++i) v = std::min(v, route.segments()[i].speed_limit_ms);
    e_static_[k] = 0.5 * v * v;
  }
  // Braking curves: sweep backwards from the stop with full braking (RK4 in e), never above
  // the static limit.
  e_.assign(samples + 1, 0.0);
  e_[samples] = 0.0;
  for (std::size_t k = samples; k-- > 0;) {
    const double track = route.at((static_cast<double>(k) + 0.5) * h_).track_N_per_kN();
    const double e1 = e_[k + 1];
    const double k1 = backward_brake_slope(train, e1, track);
    const double k2 = backward_brake_slope(train, e1 + 0.5 * h_ * k1, track);
    const double k3 = backward_brake_slope(train, e1 + 0.5 * h_ * k2, track);
    const double k4 = backward_brake_slope(train, e1 + h_ * k3, track);
    const double e_brake = e1 + h_ / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
    e_[k] = std::min(e_static_[k], e_brake);
  }
}

double SpeedEnvelope::v_at(double s_m) const {
  return std::sqrt(2.0 * std::max(0.0, e_at(s_m)));
}

}  // namespace ecorail::physics
