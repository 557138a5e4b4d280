// The contest's overlap model of regenerated energy. A train's run splits into braking phases
// (maximal stretches of braking force) and traction stretches. For a braking phase p of a train,
// the energy another train uses is E_reg(p) * t_overlap / t_brake: the phase's regenerated
// energy times the fraction of the phase during which the other train is in traction. In the
// contest's rule the other train is the one ahead (variant `ahead`); variant `either` takes
// the union of the traction of the train ahead and the train behind. All trains run the same
// pattern, so what a pair exchanges depends only on their headway; the tables here give it for
// every whole-second headway, exactly (interval arithmetic on the re-simulated trajectory, no
// time grid): used_ahead(h) (the follower brakes while the leader, h ahead, is in traction),
// used_behind(h) (the leader brakes while the follower, h behind, is in traction) and the
// double count of the union, double_count(a, b), when both neighbours draw at once.
#pragma once

#include <vector>

#include "energy/fleet_energy.hpp"
#include "energy/model_options.hpp"
#include "physics/trip.hpp"

namespace ecorail::energy {

struct Interval {
  double begin_s = 0.0, end_s = 0.0;
};

struct BrakingPhase {
  Interval time;
  double regen_J = 0.0;
};

class OverlapModel {
 public:
  // trip departs at 0.
  explicit OverlapModel(const physics::Trip& trip);

  const std::vector<Interval>& traction() const { return traction_; }
  const std::vector<BrakingPhase>& braking() const { return braking_; }
  double trip_traction_J() const { return traction_J_; }
  double trip_regen_J() const { return regen_J_; }

  // Used regenerated energy of a braking train whose neighbour departs `ahead_s` earlier
  // (traction of the train ahead), or `behind_s` later (traction of the train behind).
  double used_from_ahead_J(double ahead_s) const;
  double used_from_behind_J(double behind_s) const;
  // Union of both neighbours' traction: used_from_ahead + used_from_behind - double_count.
  double used_from_either_J(double ahead_s, double behind_s) const;
  double double_count_J(double ahead_s, double behind_s) const;

  // Used regenerated energy of train k's braking, fed by its neighbours in departures t.
  double train_used_J(const std::vector<int>& t, std::size_t k, OverlapVariant variant) const;
  // The fleet's energy for departures sorted by time (whole seconds).
  FleetEnergy evaluate(const std::vector<int>& departures_s, OverlapVariant variant) const;

 private:
  // Measure of [a, b) inside traction shifted by `shift` (and, with a second shift, inside
  // both shifted copies at once).
  double traction_overlap(double a, double b, double shift) const;
  double traction_overlap2(double a, double b, double shift1, double shift2) const;
  // Used energy of the braking phases when the other train's traction is shifted by shift_s.
  double used_with_traction_shift(double shift_s) const;

  std::vector<Interval> traction_;
  std::vector<BrakingPhase> braking_;
  double traction_J_ = 0.0, regen_J_ = 0.0;
};

}  // namespace ecorail::energy
