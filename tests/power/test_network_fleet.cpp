// The network model on a small fleet (the reference train on A6 -> A9): with zero conductor
// resistance, no auxiliaries and a lossless train it is the power-flow model exactly; a day's
// energy balance closes; moving trains one at a time gives exactly the totals of a fresh
// placement; the totals do not depend on the thread count.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "energy/fleet_energy_model.hpp"
#include "power/network_balance.hpp"
#include "power/network_evaluation.hpp"
#include "tests/fleet/fleet_fixture.hpp"

namespace ecorail::fleet {
namespace {

using power::NetworkEvaluation;

using testing::small_fleet;
using testing::small_pattern;

std::shared_ptr<const power::PowerSupply> supply(double r_per_km, double aux_W) {
  auto s = std::make_shared<power::PowerSupply>();
  s->substations = {{"S1", 0.0, 835.0, 0.015, false}, {"S2", 2500.0, 835.0, 0.015, false}};
  s->conductors = {{0.0, r_per_km * 0.4, r_per_km * 0.6}};
  s->max_train_voltage_V = 900.0;
  s->min_train_voltage_V = 500.0;
  s->auxiliary_power_W = aux_W;
  return s;
}

const FleetProblem kFleet = small_fleet(8, 40, 120, 550);

std::vector<int> departures() {
  return departures_from_headways({70, 40, 95, 60, 120, 45, 120});
}

EnergyModelOptions network(double r_per_km, double aux_W) {
  EnergyModelOptions o;
  o.model = "network";
  o.time_step_s = 0.1;
  o.power_supply = supply(r_per_km, aux_W);
  return o;
}

TEST(NetworkFleet, ZeroResistanceIsThePowerFlowModel) {
  EnergyModelOptions pf;
  pf.time_step_s = 0.1;
  const auto t = departures();
  const FleetEvaluation a = TestFleet(small_pattern().trip, kFleet, pf).evaluate(t);
  const FleetEvaluation b = TestFleet(small_pattern().trip, kFleet, network(0.0, 0.0)).evaluate(t);
  ASSERT_TRUE(b.network);
  EXPECT_GT(a.total.used_regen_J, 0.0);  // the trains do exchange energy
  EXPECT_NEAR(b.network->substation_J, a.total.substation_J(), 1e-9 * a.total.traction_J);
  EXPECT_NEAR(b.network->regen_J - b.network->curtailed_regen_J, a.total.used_regen_J,
              1e-9 * a.total.traction_J);
  EXPECT_EQ(b.network->line_losses_J, 0.0);
}

TEST(NetworkFleet, TheEnergyBalanceClosesAtEveryInstantAndOverTheDay) {
  const FleetEvaluation e =
      TestFleet(small_pattern().trip, kFleet, network(0.023, 1.5e5)).evaluate(departures());
  const NetworkEvaluation& n = *e.network;
  EXPECT_EQ(n.unsolved_instants, 0);
  EXPECT_LT(n.max_balance_error_fraction, 1e-9);
  const double lhs = n.substation_J + n.used_regen_J;
  const double rhs = n.traction_input_J + n.auxiliary_J + n.line_losses_J;
  EXPECT_LT(std::fabs(lhs - rhs), 1e-9 * rhs);
  EXPECT_GT(n.line_losses_J, 0.0);
  // Auxiliaries: every train's time on the line.
  EXPECT_NEAR(n.auxiliary_J, 8 * 1.5e5 * small_pattern().trip.arrival_s(), 1e-3);
  double per_substation = 0.0;
  for (const auto& s : n.substations) per_substation += s.energy_J;
  EXPECT_NEAR(per_substation, n.substation_J, 1e-6 * n.substation_J);
}

TEST(NetworkFleet, MovesGiveExactlyTheTotalsOfAFreshPlacement) {
  const TestFleet models(small_pattern().trip, kFleet, network(0.023, 1.5e5));
  const NetworkSetup setup = models.network_setup();
  NetworkBalance moved(*setup.profile, *setup.supply, 1.0, kFleet.trains, setup.horizon_s, 1);
  std::vector<int> t = departures();
  moved.place_all(t);
  std::uint64_t x = 12345;
  for (int m = 0; m < 60; ++m) {
    x = x * 6364136223846793005ULL + 1442695040888963407ULL;
    const int k = 1 + static_cast<int>((x >> 33) % (kFleet.trains - 2));
    const int lo = std::max(t[k - 1] + kFleet.headway_min_s, t[k + 1] - kFleet.headway_max_s);
    const int hi = std::min(t[k - 1] + kFleet.headway_max_s, t[k + 1] - kFleet.headway_min_s);
    if (hi < lo) continue;
    t[k] = lo + static_cast<int>((x >> 13) % (hi - lo + 1));
    moved.move(k, t[k]);
  }
  NetworkBalance fresh(*setup.profile, *setup.supply, 1.0, kFleet.trains, setup.horizon_s, 2);
  fresh.place_all(t);
  EXPECT_EQ(moved.substation(), fresh.substation());
  EXPECT_EQ(moved.total().losses, fresh.total().losses);
  EXPECT_EQ(moved.total().curtailed_regen, fresh.total().curtailed_regen);
  EXPECT_EQ(moved.recount().substation, moved.substation());
  // And the balance agrees with the full evaluation of the same departures.
  const NetworkEvaluation full = evaluate_network(setup, t);
  EXPECT_NEAR(to_joules(fresh.substation()), full.substation_J, 1e-6);
}

TEST(NetworkFleet, TotalsDoNotDependOnTheThreadCount) {
  const TestFleet models(small_pattern().trip, kFleet, network(0.023, 1.5e5));
  NetworkSetup one = models.network_setup(1), two = models.network_setup(2);
  const NetworkEvaluation a = evaluate_network(one, departures());
  const NetworkEvaluation b = evaluate_network(two, departures());
  EXPECT_EQ(a.substation_J, b.substation_J);
  EXPECT_EQ(a.line_losses_J, b.line_losses_J);
  EXPECT_EQ(a.curtailed_regen_J, b.curtailed_regen_J);
  EXPECT_EQ(a.min_train_voltage_V, b.min_train_voltage_V);
}

}  // namespace
}  // namespace ecorail::fleet
