// Safe separation between consecutive trains on one track (question 2.2): at every instant a
// following train's speed satisfies v <= min(v_line, sqrt(2 L b)), L the distance it has to the
// train ahead (the gap between the leader's rear and its own front less a safety margin; point
// trains and no margin by default) and b the full-service braking deceleration (by default the
// train's largest braking force at low speed, 10 km/h, divided by its mass). v_line is the speed
// envelope's business (the simulator follows it anyway); this file gives the moving part: the
// cap behind a leader's actual run, as a physics::SpeedCap in a follower section's coordinates,
// and the scan of a follower's run against it (margins in km/h and m, and where the cap binds).
// A leader that has arrived at its last stop has left the line (turned back or stabled) and
// constrains nobody.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "physics/simulator.hpp"
#include "physics/train.hpp"
#include "physics/trip.hpp"

namespace ecorail::service {

struct SeparationOptions {
  double train_length_m = 0.0;   // 0: point trains
  double safety_margin_m = 0.0;  // kept free behind the train ahead
  double braking_m_s2 = 0.0;     // 0: default_separation_braking_m_s2(train)
  bool IsValid(std::string* error) const;
};

// The train's largest braking force at 10 km/h (regenerative envelope plus pneumatic brake,
// within its deceleration limit) divided by its mass.
double default_separation_braking_m_s2(const physics::Train& train);

// The cap for a gap of gap_m: sqrt(2 b max(0, gap)).
inline double separation_cap_ms(double gap_m, double braking_m_s2);

// Where a leader is along the run at a clock time (m; +infinity once it has arrived at its
// last stop). Walks the leader's samples forward when times are asked in increasing order and
// searches otherwise, so a scan over a follower's run costs one pass. Not thread-safe (it
// remembers where it is): one track per simulation.
class LeaderTrack {
 public:
  explicit LeaderTrack(const physics::Trip& leader);
  double position_m(double t_s) const;

 private:
  physics::Trip trip_;
  mutable std::size_t at_ = 0;
};

// The moving cap behind the leader for a follower's section that starts at section_start_m
// along the run (the cap's s is the follower's position in that section's route).
physics::SpeedCap separation_cap(const physics::Trip& leader, double section_start_m,
                                 double braking_m_s2, const SeparationOptions& options);

// A stretch of a follower's run over which it is at (or above) the cap.
struct CapStretch {
  double from_s = 0.0, to_s = 0.0;  // clock
  double from_m = 0.0, to_m = 0.0;  // along the run
  double worst_margin_kmh = 0.0;    // least cap - v over the stretch (negative: above the cap)
};

struct SeparationScan {
  // Over every sample of the follower's run while the leader is on the line.
  double min_speed_margin_kmh = 1e300;   // min (cap - v)
  double min_distance_margin_m = 1e300;  // min (L - v^2 / 2b): room beyond the braking distance
  double min_gap_m = 1e300;              // min L
  double at_s = 0.0, at_m = 0.0;         // where the speed margin is least
  // Stretches where cap - v <= binding_tolerance (the cap binds or is exceeded).
  std::vector<CapStretch> binding;
  bool exceeded = false;  // somewhere v > cap + exceed_tolerance
};

SeparationScan scan_separation(const physics::Trip& leader, const physics::Trip& follower,
                               double braking_m_s2, const SeparationOptions& options,
                               double binding_tolerance_ms = 0.01,
                               double exceed_tolerance_ms = 1e-6);

inline double separation_cap_ms(double gap_m, double braking_m_s2) {
  return gap_m > 0.0 ? std::sqrt(2.0 * braking_m_s2 * gap_m) : 0.0;
}

}  // namespace ecorail::service
