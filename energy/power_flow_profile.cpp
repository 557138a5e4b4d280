#include "energy/power_flow_profile.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace ecorail::energy {

PowerProfile::PowerProfile(const physics::Trip& trip, int ticks_per_second,
                           const std::vector<double>& boundaries_m)
    : trip_(trip),
      ticks_per_second_(ticks_per_second),
      sections_(static_cast<int>(boundaries_m.size()) + 1) {
  if (trip.empty() || trip.departure_s() != 0.0)
    throw std::invalid_argument("a power profile is built from a trip departing at 0");
  if (ticks_per_second < 1) throw std::invalid_argument("ticks_per_second must be >= 1");
  const double step = 1.0 / ticks_per_second;
  const physics::PowerBins pb = trip.power_bins(step);  // starts at 0: the departure
  span_bins_ = static_cast<std::int32_t>(pb.traction_W.size());
  for (std::size_t k = 0; k < pb.traction_W.size(); ++k) {
    PowerBin bin;
    bin.offset = static_cast<std::int32_t>(k);
    bin.traction = std::llround(pb.traction_W[k] * step * kMicroJoulesPerJoule);
    bin.regen = std::llround(pb.regen_W[k] * step * kMicroJoulesPerJoule);
    if (bin.traction == 0 && bin.regen == 0) continue;
    if (sections_ > 1) {
      const double mid = (static_cast<double>(k) + 0.5) * step;
      const double s = trip.state_at(mid).position_m;
      bin.section = static_cast<std::int32_t>(
          std::upper_bound(boundaries_m.begin(), boundaries_m.end(), s) - boundaries_m.begin());
    }
    traction_total_ += bin.traction;
    regen_total_ += bin.regen;
    bins_.push_back(bin);
  }
  fill_dense();
}

void PowerProfile::fill_dense() {
  dense_traction_.clear();
  dense_regen_.clear();
  if (sections_ != 1) return;
  dense_traction_.assign(static_cast<std::size_t>(span_bins_), 0);
  dense_regen_.assign(static_cast<std::size_t>(span_bins_), 0);
  for (const PowerBin& b : bins_) {
    dense_traction_[static_cast<std::size_t>(b.offset)] = b.traction;
    dense_regen_[static_cast<std::size_t>(b.offset)] = b.regen;
  }
}

PowerProfile PowerProfile::from_bins(int ticks_per_second, std::int32_t span_bins,
                                     std::vector<PowerBin> bins) {
  if (ticks_per_second < 1) throw std::invalid_argument("ticks_per_second must be >= 1");
  PowerProfile p;
  p.ticks_per_second_ = ticks_per_second;
  p.span_bins_ = span_bins;
  for (const PowerBin& b : bins) {
    if (b.offset < 0 || b.offset >= span_bins || b.section != 0 || b.traction < 0 || b.regen < 0)
      throw std::invalid_argument("a power bin outside the span, of another section or negative");
    p.traction_total_ += b.traction;
    p.regen_total_ += b.regen;
  }
  p.bins_ = std::move(bins);
  p.fill_dense();
  return p;
}

}  // namespace ecorail::energy
