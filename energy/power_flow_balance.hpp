// PowerBalance: the power-flow model's instantaneous power balance of a fleet on one time grid
// (power-flow and sections models; the DC network's load flow is power/network_balance.hpp). Every
// supply section holds, per bin, the traction and regenerated energy of all trains in it; the
// regenerated energy used in a bin is min(regenerated, traction) of its section, and the substation
// supplies traction less that. Trains are placed at whole-second departures and can be moved one at
// a time: a move touches only the bins of the moved train's profile, and every total is an integer
// (micro-joules), so any sequence of moves gives exactly the totals of a fresh evaluation. Inside a
// bin the powers are the bin's means, so a coarse grid overstates simultaneity; docs/fleet.md shows
// how the used energy converges with the step.
#pragma once

#include <vector>

#include "energy/fleet_energy.hpp"
#include "energy/power_flow_profile.hpp"

namespace ecorail::energy {

class PowerBalance {
 public:
  // profiles[k] is train k's profile (trains may share one); all on the same grid and with the
  // same supply sections. horizon_s: the clock time past which no train runs.
  PowerBalance(std::vector<const PowerProfile*> profiles, double horizon_s);

  int trains() const { return static_cast<int>(profiles_.size()); }
  bool placed(int train) const { return departure_s_[train] >= 0; }
  int departure_s(int train) const { return departure_s_[train]; }
  // Lays every train at its departure (whole seconds >= 0), replacing any earlier placement.
  void place_all(const std::vector<int>& departures_s);
  // Moves one placed train; returns the change of used regenerated energy.
  MicroJoules move(int train, int departure_s);
  // The used regenerated energy with `train` at each of `departures_s` (the rest as placed),
  // into used_J (one per departure); the balance is left as it was. The train is lifted once
  // and each departure priced by one read-only pass over its bins (a move writes two), with the
  // same integers a move would give.
  void used_at(int train, const std::vector<int>& departures_s, std::vector<MicroJoules>& used_J);
  // set_profile(k, profile) for every train k, laid afresh: traction and regen summed per bin
  // over the trains first and the min taken once per bin (one pass per train, no min per
  // train), the same integers as one train at a time.
  void set_profile_all(const PowerProfile* profile);
  // Gives one train another profile (same grid and sections), keeping its departure: the
  // train's own pattern changes (per-train patterns) without rebuilding the balance.
  void set_profile(int train, const PowerProfile* profile);
  // The change of substation energy (traction - used) that set_profile(train, &candidate)
  // would make, computed without changing anything (so candidates can be priced in parallel).
  MicroJoules substation_change_if(int train, const PowerProfile& candidate) const;
  // The change of used energy that move(train, departure_s) would make, computed without
  // changing anything (one read-only pass; a move and its undo write four).
  MicroJoules used_change_if_moved(int train, int departure_s) const;

  MicroJoules used() const { return used_; }
  MicroJoules traction() const { return traction_; }
  MicroJoules regen() const { return regen_; }
  FleetEnergy energy() const;
  // Per supply section: traction, regen and used energy of the trains while in it.
  std::vector<FleetEnergy> section_energy() const;
  // Per train: its traction and regen, and the used energy attributed to it as a producer (its
  // share of the regenerated energy in each bin).
  std::vector<FleetEnergy> train_energy() const;
  // Used energy recomputed from the bins (a check of the running total).
  MicroJoules recount_used() const;
  // Power over [from_s, to_s) every bin: total traction, regenerated and used (W).
  struct Trace {
    double start_s = 0.0, step_s = 0.0;
    std::vector<double> traction_W, regen_W, used_W;
  };
  Trace trace(double from_s, double to_s) const;

 private:
  void add(int train, int departure_s, int sign);
  // The change of used energy that adding `profile` at `departure_s` would make (read only).
  MicroJoules gain_if_added(const PowerProfile& profile, int departure_s) const;
  // The change of used energy that replacing `now` placed at bin base_now by `next` at
  // base_next would make (read only).
  MicroJoules used_change_if_swapped(const PowerProfile& now, long base_now,
                                     const PowerProfile& next, long base_next) const;
  void check_grid(const PowerProfile& profile) const;
  // Traction, regenerated and used energy summed over bins of one or several sections.
  struct BinSum {
    MicroJoules traction = 0, regen = 0, used = 0;
  };
  void accumulate(BinSum& sum, int section, long bin) const;
  std::size_t index(int section, long bin) const {
    return static_cast<std::size_t>(section) * static_cast<std::size_t>(bins_) +
           static_cast<std::size_t>(bin);
  }

  std::vector<const PowerProfile*> profiles_;
  std::vector<int> departure_s_;
  int ticks_per_second_ = 1;
  int sections_ = 1;
  long bins_ = 0;
  std::vector<MicroJoules> traction_bins_, regen_bins_;
  MicroJoules used_ = 0, traction_ = 0, regen_ = 0;
};

}  // namespace ecorail::energy
