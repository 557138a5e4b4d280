// The DC load flow against closed forms (one train and one substation: the quadratic; zero
// resistance: the single-section power balance; huge resistance: no exchange), the diode and
// curtailment rules on cases computed by hand, and energy conservation on random instants.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include "power/load_flow.hpp"

namespace ecorail::power {
namespace {

PowerSupply one_substation(double r_per_km, bool reversible = false) {
  PowerSupply s;
  s.substations = {{"S1", 0.0, 825.0, 0.015, reversible}};
  s.conductors = {{0.0, r_per_km / 2.0, r_per_km / 2.0}};
  s.max_train_voltage_V = 900.0;
  s.min_train_voltage_V = 500.0;
  return s;
}

LoadFlowResult solve(const PowerSupply& s, const std::vector<TrainLoad>& loads) {
  LoadFlow flow(s);
  LoadFlowResult r;
  flow.solve(loads.data(), static_cast<int>(loads.size()), &r, true);
  return r;
}

double relative(double a, double b) {
  return std::fabs(a - b) / std::max(1.0, std::fabs(b));
}

TEST(LoadFlow, OneTrainOneSubstationMatchesTheQuadratic) {
  const PowerSupply s = one_substation(0.023);
  for (double p_W : {0.2e6, 1.0e6, 1.5e6}) {
    for (double x_m : {0.0, 1500.0, 3000.0}) {
      const double r_ohm = 0.015 + 0.023 * x_m / 1000.0;
      const double disc = 825.0 * 825.0 - 4.0 * r_ohm * p_W;
      ASSERT_GT(disc, 0.0);
      const double v = 0.5 * (825.0 + std::sqrt(disc));
      const LoadFlowResult r = solve(s, {{x_m, p_W - 1e5, 1e5, 0.0}});
      ASSERT_EQ(r.summary.termination, Termination::CONVERGENCE) << r.summary.FullReport();
      EXPECT_LT(relative(r.train_voltage_V[0], v), 1e-12) << p_W << " W at " << x_m << " m";
      EXPECT_LT(relative(r.substation_current_A[0], p_W / v), 1e-12);
      EXPECT_LT(relative(r.substation_voltage_V[0], 825.0 - 0.015 * p_W / v), 1e-12);
      const double line_ohm = r_ohm - 0.015;
      EXPECT_LT(relative(r.line_losses_W, line_ohm * p_W * p_W / (v * v)), 1e-9);
      EXPECT_EQ(r.curtailed_traction_W, 0.0);
    }
  }
}

TEST(LoadFlow, ZeroResistanceIsTheSingleSectionPowerBalance) {
  PowerSupply s = one_substation(0.0);
  s.substations.push_back({"S2", 8000.0, 835.0, 0.02, false});
  // (traction, regen) of two trains: the used regenerated power is min(sum R, sum T) and the
  // substations supply the rest of the traction, exactly as in the power-flow model.
  const double cases[][4] = {{2e6, 0.0, 0.0, 1.2e6},
                             {2e6, 0.0, 0.0, 2.5e6},
                             {0.3e6, 0.1e6, 0.2e6, 0.9e6},
                             {0.0, 0.0, 0.0, 1e6},
                             {1e6, 0.0, 0.0, 1e6}};
  for (const auto& c : cases) {
    const LoadFlowResult r = solve(s, {{2000.0, c[0], 0.0, c[1]}, {6000.0, c[2], 0.0, c[3]}});
    ASSERT_EQ(r.summary.termination, Termination::CONVERGENCE) << r.summary.FullReport();
    const double traction = c[0] + c[2], regen = c[1] + c[3];
    const double used = std::min(traction, regen);
    EXPECT_LT(std::fabs(r.used_regen_W - used), 1e-9 * (traction + regen));
    EXPECT_LT(std::fabs(r.substation_W - (traction - used)), 1e-9 * (traction + regen));
    EXPECT_EQ(r.line_losses_W, 0.0);
    EXPECT_LT(std::fabs(r.curtailed_regen_W - (regen - used)), 1e-9 * (traction + regen));
  }
}

TEST(LoadFlow, HugeResistanceExchangesNothing) {
  PowerSupply s = one_substation(1e9);
  s.substations.push_back({"S2", 10000.0, 825.0, 0.015, false});
  // A braking train at S1, an accelerating train at S2: the braking train's power cannot
  // reach the other one, so it is all burnt and S2 supplies the whole traction.
  const LoadFlowResult r = solve(s, {{0.0, 0.0, 0.0, 1.5e6}, {10000.0, 1e6, 0.0, 0.0}});
  ASSERT_EQ(r.summary.termination, Termination::CONVERGENCE) << r.summary.FullReport();
  EXPECT_LT(r.used_regen_W, 1e-3);
  EXPECT_LT(std::fabs(r.curtailed_regen_W - 1.5e6), 1e-3);
  EXPECT_LT(std::fabs(r.substation_power_W[1] - 1e6), 1e-3);
  EXPECT_LT(std::fabs(r.substation_power_W[0]), 1e-3);
  EXPECT_DOUBLE_EQ(r.train_voltage_V[0], 900.0);
}

TEST(LoadFlow, DiodeBlocksAndRegenerationIsBurntAtTheLimit) {
  // A braking train alone with a unidirectional substation: nowhere for its surplus to go;
  // it holds the line at the maximum voltage and burns regen - auxiliaries.
  const PowerSupply s = one_substation(0.023);
  const LoadFlowResult r = solve(s, {{2000.0, 0.0, 1e5, 1e6}});
  ASSERT_EQ(r.summary.termination, Termination::CONVERGENCE) << r.summary.FullReport();
  EXPECT_DOUBLE_EQ(r.train_voltage_V[0], 900.0);
  EXPECT_NEAR(r.curtailed_regen_W, 0.9e6, 1e-6);
  EXPECT_EQ(r.substation_current_A[0], 0.0);
  EXPECT_EQ(r.substation_W, 0.0);
  EXPECT_EQ(r.summary.regen_curtailed_buses, 1);
}

TEST(LoadFlow, ReversibleSubstationTakesTheSurplusBackByTheQuadratic) {
  const PowerSupply s = one_substation(0.023, true);
  const double r_ohm = 0.015 + 0.023 * 2.0;
  const double surplus = 0.9e6;  // regen 1 MW less auxiliaries 0.1 MW
  const double i = (-825.0 + std::sqrt(825.0 * 825.0 + 4.0 * r_ohm * surplus)) / (2.0 * r_ohm);
  const LoadFlowResult r = solve(s, {{2000.0, 0.0, 1e5, 1e6}});
  ASSERT_EQ(r.summary.termination, Termination::CONVERGENCE) << r.summary.FullReport();
  EXPECT_LT(relative(-r.substation_current_A[0], i), 1e-12);
  EXPECT_LT(relative(r.train_voltage_V[0], 825.0 + r_ohm * i), 1e-12);
  EXPECT_LT(relative(-r.substation_power_W[0], (825.0 + 0.015 * i) * i), 1e-12);
  EXPECT_EQ(r.curtailed_regen_W, 0.0);
  // More regeneration than the line can carry below 900 V: held at 900 V, the rest burnt.
  const double i_max = (900.0 - 825.0) / r_ohm;
  const LoadFlowResult big = solve(s, {{2000.0, 0.0, 1e5, 3e6}});
  ASSERT_EQ(big.summary.termination, Termination::CONVERGENCE) << big.summary.FullReport();
  EXPECT_DOUBLE_EQ(big.train_voltage_V[0], 900.0);
  EXPECT_LT(relative(big.curtailed_regen_W, 2.9e6 - 900.0 * i_max), 1e-12);
  EXPECT_LT(relative(-big.substation_current_A[0], i_max), 1e-12);
}

TEST(LoadFlow, TractionIsCurtailedAtTheMinimumVoltage) {
  const PowerSupply s = one_substation(0.023);
  const double r_ohm = 0.015 + 0.023 * 5.0;
  const double i_min = (825.0 - 500.0) / r_ohm;  // the current that leaves 500 V at the train
  // 1.0 MW has a solution above 500 V; 1.28 MW has one only below (curtailed to 500 V);
  // 1.5 MW has none at all (4 R P > U0^2): curtailed the same way, the event counted.
  for (double p_W : {1.28e6, 1.5e6}) {
    const LoadFlowResult r = solve(s, {{5000.0, p_W, 0.0, 0.0}});
    ASSERT_EQ(r.summary.termination, Termination::CONVERGENCE) << r.summary.FullReport();
    EXPECT_DOUBLE_EQ(r.train_voltage_V[0], 500.0);
    EXPECT_LT(relative(r.traction_W, 500.0 * i_min), 1e-12);
    EXPECT_LT(relative(r.curtailed_traction_W, p_W - 500.0 * i_min), 1e-12);
    EXPECT_EQ(r.summary.traction_curtailed_buses, 1);
  }
  const LoadFlowResult ok = solve(s, {{5000.0, 1.0e6, 0.0, 0.0}});
  EXPECT_EQ(ok.curtailed_traction_W, 0.0);
  EXPECT_GT(ok.train_voltage_V[0], 500.0);
}

// Counter-based uniform numbers for the random instants.
double uniform(std::uint64_t k) {
  k += 0x9e3779b97f4a7c15ULL;
  k = (k ^ (k >> 30)) * 0xbf58476d1ce4e5b9ULL;
  k = (k ^ (k >> 27)) * 0x94d049bb133111ebULL;
  return static_cast<double>((k ^ (k >> 31)) >> 11) * 0x1.0p-53;
}

TEST(LoadFlow, ConservesEnergyOnRandomInstants) {
  PowerSupply s;
  s.max_train_voltage_V = 900.0;
  s.min_train_voltage_V = 500.0;
  s.conductors = {{0.0, 0.008, 0.015}, {9000.0, 0.0, 0.0}, {9500.0, 0.012, 0.02}};
  for (int i = 0; i < 6; ++i)
    s.substations.push_back(
        {"S" + std::to_string(i), 4000.0 * i, 800.0 + 10.0 * i, 0.01 + 0.005 * i, i == 3});
  LoadFlow flow(s);
  LoadFlowResult r;
  std::uint64_t c = 0;
  int curtailed = 0, unsolved = 0;
  for (int instant = 0; instant < 3000; ++instant) {
    std::vector<TrainLoad> loads(1 + instant % 8);
    for (auto& l : loads) {
      const double km = std::round(uniform(c++) * 22);
      l.position_m = km * 1000.0 + (uniform(c++) < 0.5 ? 0.0 : 333.0);
      const double u = uniform(c++);
      l.auxiliary_W = 1.5e5;
      if (u < 0.4)
        l.traction_W = uniform(c++) * 3e6;
      else if (u < 0.8)
        l.regen_W = uniform(c++) * 3e6;
    }
    flow.solve(loads.data(), static_cast<int>(loads.size()), &r);
    // An instant the active set cannot settle is flagged, never passed off as a solution.
    if (r.summary.termination != Termination::CONVERGENCE) {
      ++unsolved;
      EXPECT_FALSE(r.summary.IsSolutionUsable());
      continue;
    }
    const double scale = r.traction_W + r.auxiliary_W + r.regen_W;
    EXPECT_LT(std::fabs(r.balance_residual_W()), 1e-9 * scale) << instant;
    double sum = 0.0;
    for (double p : r.substation_power_W) sum += p;
    EXPECT_LT(std::fabs(sum - r.substation_W), 1e-9 * scale);
    for (std::size_t k = 0; k < loads.size(); ++k) {
      EXPECT_LE(r.train_voltage_V[k], 900.0 * (1 + 1e-12));
      EXPECT_GE(r.train_curtailed_regen_W[k], 0.0);
      EXPECT_LE(r.train_curtailed_regen_W[k], loads[k].regen_W * (1 + 1e-12));
    }
    for (std::size_t k = 0; k < s.substations.size(); ++k)
      if (!s.substations[k].reversible) {
        EXPECT_GE(r.substation_current_A[k], -1e-6);  // the diode's tolerance: 1e-9 V
      }
    curtailed += r.curtailed_regen_W > 0.0 || r.curtailed_traction_W > 0.0;
  }
  EXPECT_GT(curtailed, 0);  // the random instants do exercise the limits
  // Known weakness (docs/power_network.md): on dense random instants far harsher than a
  // timetable's, the active set cycles on a handful.
  EXPECT_LE(unsolved, 3);  // 1 of the 3000 when written
}

}  // namespace
}  // namespace ecorail::power
