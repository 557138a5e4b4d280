// The train model and the integrator: the acceleration limit, the envelopes, the speed envelope
// (limits and braking curves) and the energy ledger's work-energy balance.
#include <gtest/gtest.h>

#include <cmath>

#include "data/line_loader.hpp"
#include "data/route_builder.hpp"
#include "physics/simulator.hpp"
#include "physics_fixtures.hpp"

namespace ecorail {
namespace {

TEST(TrainModel, ReferenceEnvelopesMatchModelTables) {
  const physics::Train train = data::default_train();
  EXPECT_NEAR(train.traction.force_kN_at_kmh(30.0), 203.0, 1e-12);
  const double v = 70.0;
  EXPECT_NEAR(train.traction.force_kN_at_kmh(v),
              -0.002032 * v * v * v + 0.4928 * v * v - 42.13 * v + 1343.0, 1e-9);
  EXPECT_NEAR(train.braking.force_kN_at_kmh(50.0), 166.0, 1e-12);
  EXPECT_NEAR(train.braking.force_kN_at_kmh(79.0), 0.1343 * 79 * 79 - 25.07 * 79 + 1300, 1e-9);
  // Davis resistance at 60 km/h in N: (2.031 + 0.0622*60 + 0.001807*3600) * M g / 1000.
  const double w = (2.031 + 0.0622 * 60 + 0.001807 * 3600) * 194.295 * 9.8;
  EXPECT_NEAR(train.resistance_N(units::kmh_to_ms(60.0), 0.0), w, 1e-6);
}

TEST(TrainModel, FullTractionIsCutToTheAccelerationLimitAtLowSpeed) {
  const physics::Train train = data::default_train();
  const physics::Route route = test::straight_track(0.0);
  const physics::SpeedEnvelope envelope(train, route, 0.5);
  const physics::Motion motion(train, route, envelope);
  // From rest, dv/dt = 1 m/s^2 exactly while the cut is active: v^2 = 2 a s.
  const auto adv = motion.advance(0.0, 0.0, 10.0, physics::Control::MaxTraction, {0.05, 4});
  EXPECT_NEAR(physics::speed_from_e(adv.e_end), std::sqrt(2.0 * 10.0), 1e-9);
  EXPECT_NEAR(adv.time_s, std::sqrt(2.0 * 10.0), 1e-6);
  // The force applied is M * 1 + W, less than the 203 kN envelope.
  const double v = 5.0;
  const double w = train.resistance_N(v, 0.0);
  EXPECT_NEAR(train.max_traction_N(v, w), train.effective_mass_kg() + w, 1e-6);
  EXPECT_LT(train.max_traction_N(v, w), 203000.0);
}

TEST(SpeedEnvelope, FlatOutRunRespectsLimitsAndStopsAtTheStation) {
  const data::Line line = data::default_line();
  const physics::Train train = data::default_train();
  for (auto [from, to] : {std::pair{"A6", "A7"}, std::pair{"A1", "A2"}, std::pair{"A3", "A4"},
                          std::pair{"A13", "A14"}}) {
    const physics::Route route = data::build_route(line, from, to, train);
    const physics::SpeedEnvelope envelope(train, route);
    const physics::Motion motion(train, route, envelope);
    const auto sim = physics::simulate(motion, {{0.0, physics::Control::MaxTraction}}, {});
    EXPECT_FALSE(sim.stopped_early) << from;
    EXPECT_LT(std::abs(sim.stop_error_m), 0.01) << from;
    EXPECT_LT(sim.max_overspeed_ms, units::kmh_to_ms(0.05)) << from;
    // Never above the line's limit at any trace point.
    for (const auto& p : sim.trace) {
      ASSERT_LE(p.v_ms, route.speed_limit_ms(p.s_m) + units::kmh_to_ms(0.05)) << from << p.s_m;
    }
  }
}

TEST(EnergyLedger, WorkEnergyBalanceCloses) {
  // Traction work - braking work - resistance work = change of kinetic energy (= 0, rest to
  // rest). Resistance work is integrated here independently from the trace.
  const data::Line line = data::default_line();
  const physics::Train train = data::default_train();
  const physics::Route route = data::build_route(line, "A6", "A7", train);
  const physics::SpeedEnvelope envelope(train, route);
  const physics::Motion motion(train, route, envelope);
  const auto sim = physics::simulate(
      motion, {{0.0, physics::Control::MaxTraction}, {300.0, physics::Control::Coast}}, {});
  double resistance_work = 0.0;
  for (std::size_t k = 1; k < sim.trace.size(); ++k) {
    const auto& a = sim.trace[k - 1];
    const auto& b = sim.trace[k];
    const double mid = 0.5 * (a.s_m + b.s_m);
    const double v = 0.5 * (a.v_ms + b.v_ms);
    resistance_work += train.resistance_N(v, route.at(mid).track_N_per_kN()) * (b.s_m - a.s_m);
  }
  const double balance = sim.energy.traction_work_J - sim.energy.brake_work_J - resistance_work;
  EXPECT_NEAR(balance, 0.0, 1e-3 * sim.energy.traction_work_J);
  EXPECT_NEAR(sim.energy.regen_J, 0.95 * sim.energy.brake_work_J, 1e-6);
}

}  // namespace
}  // namespace ecorail
