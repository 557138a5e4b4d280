// Closed-form coasting against the distance integrator, on flat track, on a 10 per mille climb
// and on a 20 per mille descent where the train converges to its balancing speed.
#include <gtest/gtest.h>

#include <ostream>

#include <cmath>

#include "physics/coasting.hpp"
#include "physics/motion.hpp"
#include "physics_fixtures.hpp"

namespace ecorail {
namespace {

struct CoastCase {
  const char* name;
  double gradient_permille;
  double v0_kmh;
  double distance_m;
};

// Printed in test listings by name and gradient, not as raw bytes.
void PrintTo(const CoastCase& c, std::ostream* os) {
  *os << c.name << " (" << c.gradient_permille << " per mille from " << c.v0_kmh << " km/h)";
}

class CoastingAgreement : public ::testing::TestWithParam<CoastCase> {};

TEST_P(CoastingAgreement, IntegratorMatchesClosedFormToOnePartPerMillion) {
  const CoastCase c = GetParam();
  const physics::Train train = test::unconstrained_train();
  const physics::Route route = test::straight_track(c.gradient_permille);
  const physics::SpeedEnvelope envelope(train, route, 0.5);
  const physics::Motion motion(train, route, envelope);
  const physics::CoastingCurve curve(train, c.gradient_permille);

  const double v0 = units::kmh_to_ms(c.v0_kmh);
  const physics::StepSettings fine{0.05, 4};
  double s = 0.0, e = 0.5 * v0 * v0, t = 0.0;
  // Compare at several distances along the coast, not only at its end.
  for (int k = 1; k <= 4; ++k) {
    const double target = c.distance_m * k / 4.0;
    const physics::Advance adv = motion.advance(s, e, target, physics::Control::Coast, fine);
    ASSERT_FALSE(adv.stalled);
    s = target;
    e = adv.e_end;
    t += adv.time_s;
    const double v_closed = curve.speed_after_m(v0, target);
    const double t_closed = curve.time_after_m(v0, target);
    EXPECT_NEAR(physics::speed_from_e(e), v_closed, 1e-6 * v_closed) << c.name << " at " << s;
    EXPECT_NEAR(t, t_closed, 1e-6 * t_closed) << c.name << " at " << s;
    EXPECT_NEAR(curve.distance_m(v0, v_closed), target, 1e-6 * target);
  }
}

INSTANTIATE_TEST_SUITE_P(Gradients, CoastingAgreement,
                         ::testing::Values(CoastCase{"flat", 0.0, 70.0, 1500.0},
                                           CoastCase{"climb_10", 10.0, 70.0, 500.0},
                                           CoastCase{"descent_20_from_below", -20.0, 40.0, 3000.0},
                                           CoastCase{"descent_20_from_above", -20.0, 120.0,
                                                     3000.0}),
                         [](const auto& info) { return std::string(info.param.name); });

TEST(Coasting, DescentHasBalancingSpeedThatTheIntegratorApproaches) {
  const physics::Train train = test::unconstrained_train();
  const physics::CoastingCurve curve(train, -20.0);
  ASSERT_TRUE(curve.has_balancing_speed());
  const double vb = curve.balancing_speed_ms();
  // At the balancing speed resistance and gradient cancel.
  EXPECT_NEAR(curve.deceleration(vb), 0.0, 1e-12);
  // Davis resistance at vb equals the 20 per mille pull: (A + B v + C v^2) = 20 with v in km/h.
  const double v = units::ms_to_kmh(vb);
  EXPECT_NEAR(train.davis.A + train.davis.B * v + train.davis.C * v * v, 20.0, 1e-9);
  // After a long coast from 40 km/h the integrator is close to vb but still below it.
  const physics::Route route = test::straight_track(-20.0, 40000.0);
  const physics::SpeedEnvelope envelope(train, route, 1.0);
  const physics::Motion motion(train, route, envelope);
  const double v0 = units::kmh_to_ms(40.0);
  const auto adv = motion.advance(0.0, 0.5 * v0 * v0, 30000.0, physics::Control::Coast, {0.5, 4});
  const double v_end = physics::speed_from_e(adv.e_end);
  EXPECT_LT(v_end, vb);
  EXPECT_GT(v_end, 0.99 * vb);
}

TEST(Coasting, FlatTrackStopsAtTheClosedFormDistance) {
  const physics::Train train = test::unconstrained_train();
  const physics::CoastingCurve curve(train, 0.0);
  const double v0 = units::kmh_to_ms(30.0);
  const double d_stop = curve.distance_m(v0, 0.0);
  EXPECT_DOUBLE_EQ(curve.speed_after_m(v0, d_stop + 1.0), 0.0);
  const physics::Route route = test::straight_track(0.0);
  const physics::SpeedEnvelope envelope(train, route, 0.5);
  const physics::Motion motion(train, route, envelope);
  // Integrating past the stop distance stalls within a few centimetres of it.
  double s = 0.0, e = 0.5 * v0 * v0;
  while (true) {
    const physics::Substep sub = motion.substep(s, e, 0.01, physics::Control::Coast, 4);
    s += sub.length_m;
    e = sub.e_end;
    if (sub.stopped) break;
  }
  EXPECT_NEAR(s, d_stop, 0.02);
}

}  // namespace
}  // namespace ecorail
