#include "power/network_profile.hpp"

#include <algorithm>
#include <stdexcept>

namespace ecorail::power {

NetworkProfile::NetworkProfile(const physics::Trip& trip, int ticks_per_second)
    : ticks_per_second_(ticks_per_second) {
  if (trip.empty() || trip.departure_s() != 0.0)
    throw std::invalid_argument("a network profile is built from a trip departing at 0");
  if (ticks_per_second < 1) throw std::invalid_argument("ticks_per_second must be >= 1");
  const double step = 1.0 / ticks_per_second;
  const physics::PowerBins pb = trip.power_bins(step);
  const double arrival = trip.arrival_s();
  for (std::size_t k = 0; k < pb.traction_W.size(); ++k) {
    const double t0 = static_cast<double>(k) * step;
    if (t0 >= arrival) break;
    const double present = std::min(1.0, (arrival - t0) / step);
    position_m_.push_back(trip.state_at(std::min(arrival, t0 + 0.5 * step)).position_m);
    traction_W_.push_back(pb.traction_W[k]);
    regen_W_.push_back(pb.regen_W[k]);
    presence_.push_back(present);
    traction_total_J_ += pb.traction_W[k] * step;
    regen_total_J_ += pb.regen_W[k] * step;
    presence_total_s_ += present * step;
  }
}

void NetworkProfile::loads_at(long bin, const long* base, const int* train_of, int count,
                              double traction_efficiency, double auxiliary_W,
                              std::vector<TrainLoad>& loads, std::vector<int>& trains) const {
  const long span = span_bins();
  const long* first = std::lower_bound(base, base + count, bin - span + 1);
  for (const long* b = first; b != base + count && *b <= bin; ++b) {
    const std::int32_t k = static_cast<std::int32_t>(bin - *b);
    loads.push_back({position_m_[k], traction_W_[k] / traction_efficiency,
                     auxiliary_W * presence_[k], regen_W_[k]});
    trains.push_back(train_of[b - base]);
  }
}

}  // namespace ecorail::power
