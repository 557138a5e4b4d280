// NetworkProfile: one train's trip on the network model's time grid. Where the power-flow
// profile (energy/power_flow_profile.hpp) needs only the energy in each bin, the network model also
// needs where the train is: per bin from the departure to the arrival, the position at the bin's
// middle, the mean traction power at the wheel and the mean regenerated power (the trip's exact
// power bins divided by the step), and the fraction of the bin the train is on the line (1 but
// for the last bin), which scales its auxiliary power. Departures are whole seconds and the
// step divides a second, so a train departing at t uses the same bins shifted by t x ticks.
// loads_at() gathers the loads of every train on the line at one bin for the load flow.
#pragma once

#include <cstdint>
#include <vector>

#include "physics/trip.hpp"
#include "power/load_flow.hpp"

namespace ecorail::power {

class NetworkProfile {
 public:
  NetworkProfile() = default;
  // trip must depart at 0.
  NetworkProfile(const physics::Trip& trip, int ticks_per_second);

  int ticks_per_second() const { return ticks_per_second_; }
  double step_s() const { return 1.0 / ticks_per_second_; }
  std::int32_t span_bins() const { return static_cast<std::int32_t>(position_m_.size()); }
  double position_m(std::int32_t k) const { return position_m_[k]; }
  double traction_W(std::int32_t k) const { return traction_W_[k]; }
  double regen_W(std::int32_t k) const { return regen_W_[k]; }
  double presence(std::int32_t k) const { return presence_[k]; }
  double traction_total_J() const { return traction_total_J_; }
  double regen_total_J() const { return regen_total_J_; }
  double presence_total_s() const { return presence_total_s_; }

  // The loads at `bin` of the trains whose first bins are base_bins[0..count) (ascending),
  // train_of[i] naming each; appends to loads (and their train numbers to trains).
  void loads_at(long bin, const long* base_bins, const int* train_of, int count,
                double traction_efficiency, double auxiliary_W, std::vector<TrainLoad>& loads,
                std::vector<int>& trains) const;

 private:
  int ticks_per_second_ = 1;
  std::vector<double> position_m_, traction_W_, regen_W_, presence_;
  double traction_total_J_ = 0.0, regen_total_J_ = 0.0, presence_total_s_ = 0.0;
};

}  // namespace ecorail::power
