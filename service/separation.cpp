#include "service/separation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace ecorail::service {

bool SeparationOptions::IsValid(std::string* error) const {
  auto fail = [&](const std::string& why) {
    if (error) *error = why;
    return false;
  };
  if (!(std::isfinite(train_length_m) && train_length_m >= 0.0 && train_length_m <= 1000.0))
    return fail("train_length_m: expected 0 to 1000 m");
  if (!(std::isfinite(safety_margin_m) && safety_margin_m >= 0.0 && safety_margin_m <= 10000.0))
    return fail("safety_margin_m: expected 0 to 10000 m");
  if (!(std::isfinite(braking_m_s2) && braking_m_s2 >= 0.0 && braking_m_s2 <= 10.0))
    return fail("braking_m_s2: expected 0 (the train's) to 10 m/s^2");
  return true;
}

double default_separation_braking_m_s2(const physics::Train& train) {
  return train.max_brake_N(10.0 / 3.6, 0.0) / train.mass_kg;
}

LeaderTrack::LeaderTrack(const physics::Trip& leader) : trip_(leader) {}

double LeaderTrack::position_m(double t_s) const {
  if (trip_.empty() || trip_.samples().empty())
    return std::numeric_limits<double>::infinity();  // no leader on the line
  const auto& samples = trip_.samples();
  const double t = t_s - trip_.departure_s();
  if (t <= 0.0) return samples.front().s_m;
  if (t >= samples.back().t_s) return std::numeric_limits<double>::infinity();
  // Forward walk from the last answer when time moves on; a search when it went back.
  if (at_ >= samples.size() - 1 || samples[at_].t_s > t) {
    at_ = static_cast<std::size_t>(
              std::upper_bound(samples.begin(), samples.end(), t,
                               [](double x, const physics::Trip::Sample& s) { return x < s.t_s; }) -
              samples.begin()) -
          1;
  }
  while (at_ + 1 < samples.size() && samples[at_ + 1].t_s <= t) ++at_;
  const auto& a = samples[at_];
  const auto& b = samples[std::min(at_ + 1, samples.size() - 1)];
  const double dt = b.t_s - a.t_s;
  if (dt <= 0.0) return a.s_m;
  const double tau = t - a.t_s;
  const double accel = (b.v_ms - a.v_ms) / dt;
  return std::min(b.s_m, a.s_m + a.v_ms * tau + 0.5 * accel * tau * tau);
}

physics::SpeedCap separation_cap(const physics::Trip& leader, double section_start_m,
                                 double braking_m_s2, const SeparationOptions& options) {
  auto track = std::make_shared<LeaderTrack>(leader);
  const double room = options.train_length_m + options.safety_margin_m;
  return [track, section_start_m, braking_m_s2, room](double t_s, double s_m) {
    const double lead = track->position_m(t_s);
    if (!std::isfinite(lead)) return std::numeric_limits<double>::infinity();
    return separation_cap_ms(lead - room - (section_start_m + s_m), braking_m_s2);
  };
}

SeparationScan scan_separation(const physics::Trip& leader, const physics::Trip& follower, double b,
                               const SeparationOptions& options, double binding_tol,
                               double exceed_tol) {
  SeparationScan out;
  const LeaderTrack track(leader);
  const double room = options.train_length_m + options.safety_margin_m;
  const double t0 = follower.departure_s();
  bool in_stretch = false;
  for (const physics::Trip::Sample& p : follower.samples()) {
    const double t = t0 + p.t_s;
    const double lead = track.position_m(t);
    if (!std::isfinite(lead)) break;  // the leader has left the line, for good
    const double gap = lead - room - p.s_m;
    const double cap = separation_cap_ms(gap, b);
    const double margin_kmh = 3.6 * (cap - p.v_ms);
    if (margin_kmh < out.min_speed_margin_kmh)
      out.min_speed_margin_kmh = margin_kmh, out.at_s = t, out.at_m = p.s_m;
    out.min_distance_margin_m =
        std::min(out.min_distance_margin_m, gap - p.v_ms * p.v_ms / (2 * b));
    out.min_gap_m = std::min(out.min_gap_m, gap);
    if (cap - p.v_ms < -exceed_tol) out.exceeded = true;
    const bool binds = cap - p.v_ms <= binding_tol && p.v_ms > 0.0;
    if (binds && !in_stretch) out.binding.push_back({t, t, p.s_m, p.s_m, margin_kmh});
    if (binds) {
      CapStretch& c = out.binding.back();
      c.to_s = t, c.to_m = p.s_m;
      c.worst_margin_kmh = std::min(c.worst_margin_kmh, margin_kmh);
    }
    in_stretch = binds;
  }
  return out;
}

}  // namespace ecorail::service
