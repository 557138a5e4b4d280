// PowerProfile: one train's power on the time grid of the power-flow and sections models (the
// balance of regenerated and traction power per time bin; not the DC load flow of power/), ready to
// be laid at any whole-second departure. Built once from a trip that departs at 0: the trip's exact
// power bins (each bin the integral of the power over it, physics::Trip::power_bins) are stored as
// integers (micro-joules per bin) in a sparse list of the bins where the train draws traction or
// feeds regenerated power. Integer energies make every sum in the fleet exact, so moving a train a
// million times leaves the same totals as a fresh evaluation. Because departures are whole seconds
// and the step divides a second, a departure shifts the profile by a whole number of bins: no
// re-binning, no re-simulation. A profile also knows, per bin, the supply section the train is
// in (by its position at the bin's middle), for the sections model.
#pragma once

#include <cstdint>
#include <vector>

#include "physics/trip.hpp"
#include "power/micro_joules.hpp"

namespace ecorail::energy {

// Energy in a bin, in micro-joules (power/micro_joules.hpp).
using power::kMicroJoulesPerJoule;
using power::MicroJoules;
using power::to_joules;

struct PowerBin {
  std::int32_t offset = 0;   // bins after the departure
  std::int32_t section = 0;  // supply section the train is in
  MicroJoules traction = 0;  // traction energy at the wheel in the bin
  MicroJoules regen = 0;     // regenerated electrical energy in the bin
};

class PowerProfile {
 public:
  PowerProfile() = default;
  // trip must depart at 0; boundaries_m split the run into supply sections.
  PowerProfile(const physics::Trip& trip, int ticks_per_second,
               const std::vector<double>& boundaries_m);
  // A profile of given bins (one section, no trip): e.g. a demand and a regeneration that are
  // not a trip's traction and braking (the network bound's traction plus auxiliaries).
  static PowerProfile from_bins(int ticks_per_second, std::int32_t span_bins,
                                std::vector<PowerBin> bins);

  int ticks_per_second() const { return ticks_per_second_; }
  int sections() const { return sections_; }
  // Bins from the departure to past the arrival.
  std::int32_t span_bins() const { return span_bins_; }
  const std::vector<PowerBin>& bins() const { return bins_; }
  // One supply section: traction and regen of every bin from the departure (zeros included),
  // span_bins() of each, for loops that shift a whole profile without a merge; empty otherwise.
  const std::vector<MicroJoules>& dense_traction() const { return dense_traction_; }
  const std::vector<MicroJoules>& dense_regen() const { return dense_regen_; }
  MicroJoules traction_total() const { return traction_total_; }
  MicroJoules regen_total() const { return regen_total_; }
  const physics::Trip& trip() const { return trip_; }

 private:
  physics::Trip trip_;
  int ticks_per_second_ = 1;
  int sections_ = 1;
  std::int32_t span_bins_ = 0;
  void fill_dense();

  std::vector<PowerBin> bins_;
  std::vector<MicroJoules> dense_traction_, dense_regen_;
  MicroJoules traction_total_ = 0;
  MicroJoules regen_total_ = 0;
};

}  // namespace ecorail::energy
