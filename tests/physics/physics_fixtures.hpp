// Shared fixtures for the physics tests: the reference train from the embedded data, and a
// long single-gradient test track on which nothing but the physics under test happens.
#pragma once

#include "data/train_io.hpp"
#include "physics/route.hpp"
#include "physics/units.hpp"

namespace ecorail::test {

// The reference train with the speed cap lifted, so coasting on a descent can reach its
// balancing speed without meeting the envelope.
inline physics::Train unconstrained_train() {
  physics::Train t = data::default_train();
  t.max_speed_ms = units::kmh_to_ms(200.0);
  return t;
}

inline physics::Route straight_track(double gradient_permille, double length_m = 20000.0,
                                     double limit_kmh = 200.0) {
  return physics::Route({{0.0, length_m, gradient_permille, 0.0, units::kmh_to_ms(limit_kmh)}}, 0.0,
                        1, "start", "end");
}

}  // namespace ecorail::test
