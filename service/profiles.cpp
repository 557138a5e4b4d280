#include "service/profiles.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>

namespace ecorail::service {

std::vector<ProfilePoint> speed_profile(const std::vector<physics::Trip>& trips, std::size_t k,
                                        double b, const SeparationOptions& options, double step_s) {
  if (k >= trips.size()) throw std::out_of_range("speed_profile: no such train");
  if (!(step_s > 0.0)) throw std::invalid_argument("speed_profile: step_s must be > 0");
  const physics::Trip& trip = trips[k];
  std::unique_ptr<LeaderTrack> leader;
  if (k > 0) leader = std::make_unique<LeaderTrack>(trips[k - 1]);
  const double room = options.train_length_m + options.safety_margin_m;
  std::vector<ProfilePoint> out;
  const double t0 = trip.departure_s(), t1 = trip.arrival_s();
  const long n = static_cast<long>(std::floor((t1 - t0) / step_s));
  for (long i = 0; i <= n + 1; ++i) {
    const double t = std::min(t1, t0 + static_cast<double>(i) * step_s);
    const physics::TripState st = trip.state_at(t);
    ProfilePoint p;
    p.clock_s = t;
    p.position_m = st.position_m;
    p.speed_ms = st.speed_ms;
    const std::size_t sec = static_cast<std::size_t>(st.section);
    const double in_section =
        std::clamp(st.position_m - trip.section_start_m(sec), 0.0, trip.route(sec).length_m());
    p.limit_ms = trip.route(sec).speed_limit_ms(in_section);
    if (leader) {
      const double lead = leader->position_m(t);
      if (std::isfinite(lead)) p.cap_ms = separation_cap_ms(lead - room - st.position_m, b);
    }
    out.push_back(p);
    if (t >= t1) break;
  }
  return out;
}

}  // namespace ecorail::service
