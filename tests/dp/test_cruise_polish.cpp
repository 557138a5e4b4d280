// The cruise polish (dp/cruise_polish.hpp): on a long level line the optimum is full traction,
// one speed hold, a coast and the final brake. The DP's run, made one hold with its coasting
// point searched, must meet its time, consist of exactly one hold, and cost no more than an
// independent optimiser of that strategy that uses only the simulator (golden section on the
// hold length, the end of traction bisected to meet the time) nor more than the grid's own
// cruise (the engine without holds), each within 0.01 %.
#include <gtest/gtest.h>

#include <cmath>

#include "data/train_io.hpp"
#include "dp/section_engine.hpp"
#include "dp/time_target.hpp"
#include "physics/units.hpp"
#include "regime_search.hpp"

namespace ecorail {
namespace {

physics::Route long_level_route() {
  physics::RouteSegment seg;
  seg.start_m = 0.0;
  seg.end_m = 8000.0;
  seg.speed_limit_ms = units::kmh_to_ms(80.0);
  return physics::Route({seg}, 0.0, 1, "L0", "L1");
}

dp::EngineOptions coarse(bool cruise_as_hold) {
  dp::EngineOptions o;
  o.grid.ds_m = 10.0;
  o.grid.dv_kmh = 0.5;
  o.grid.substep_m = 5.0;
  o.cruise_as_hold = cruise_as_hold;
  return o;
}

// Independent: "full traction, hold, coast, full brake" by the simulator alone; the energy of
// the best hold length by golden section (energy_for_hold bisects the end of traction).
double strategy_optimum_J(const physics::Motion& motion, double target_s) {
  double x1 = 0.0;
  auto e = [&](double hold) { return test::energy_for_hold(motion, target_s, hold, 0.5, &x1); };
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  double a = 500.0, b = 7000.0;
  double c = b - g * (b - a), d = a + g * (b - a);
  double fc = e(c), fd = e(d);
  while (b - a > 0.5) {
    if (fc <= fd) {
      b = d, d = c, fd = fc, c = b - g * (b - a), fc = e(c);
    } else {
      a = c, c = d, fc = fd, d = a + g * (b - a), fd = e(d);
    }
  }
  return std::min(fc, fd);
}

int holds(const physics::ControlProgram& program) {
  int n = 0;
  for (const auto& entry : program) n += entry.control == physics::Control::Hold ? 1 : 0;
  return n;
}

TEST(CruisePolish, LongLevelRunIsOneHoldAndAsCheapAsTheStrategyOptimum) {
  const physics::Train train = data::default_train();
  const physics::Route route = long_level_route();
  const dp::SectionEngine held(train, route, coarse(true));
  const dp::SectionEngine grid(train, route, coarse(false));
  const double target_s = held.min_time_run().running_time_s * 1.12;

  const dp::TimeSearchResult polished = dp::solve_for_time(held, target_s, {});
  ASSERT_TRUE(polished.converged);
  EXPECT_TRUE(dp::run_arrives(polished.run.sim));
  EXPECT_NEAR(polished.run.sim.running_time_s, target_s, 1e-3);
  EXPECT_EQ(holds(polished.run.program), 1);
  EXPECT_LE(polished.run.cost_J, polished.cruise_polish.cost_before_J);

  const dp::TimeSearchResult saw = dp::solve_for_time(grid, target_s, {});
  ASSERT_TRUE(saw.converged);
  EXPECT_NEAR(saw.run.sim.running_time_s, target_s, 1e-3);

  const double independent_J = strategy_optimum_J(held.motion(), target_s);
  ASSERT_TRUE(std::isfinite(independent_J));
  const double e = polished.run.sim.energy.traction_work_J;
  EXPECT_LE(e, independent_J * (1.0 + 1e-4))
      << "polished " << e << " J, strategy optimum " << independent_J << " J";
  EXPECT_LE(e, saw.run.sim.energy.traction_work_J * (1.0 + 1e-4))
      << "polished " << e << " J, grid cruise " << saw.run.sim.energy.traction_work_J << " J";
  // And the strategy optimum cannot beat the polished run by more than the search's tolerance:
  // both optimise the same strategy, the polish from the DP's shape.
  EXPECT_GE(e, independent_J * (1.0 - 1e-4));
}

// A cruise over a steep descent: holding the cruise speed there would brake all the way down
// (gravity outweighs the resistance); the run must coast instead and cost no more than the
// grid's own run (which coasts down the hill) beyond 0.05 %. Holding by braking cost 12 % more
// on TTOBench's 00_var_gradient_minus_10 before holds learnt to coast.
TEST(CruisePolish, ADescentIsCoastedNotBrakedThrough) {
  std::vector<physics::RouteSegment> segs(3);
  const double ends[] = {4000.0, 7000.0, 12000.0}, grades[] = {0.0, -20.0, 0.0};
  for (int i = 0; i < 3; ++i) {
    segs[i].start_m = i == 0 ? 0.0 : ends[i - 1];
    segs[i].end_m = ends[i];
    segs[i].gradient_permille = grades[i];
    segs[i].speed_limit_ms = units::kmh_to_ms(80.0);
  }
  const physics::Route route(segs, 0.0, 1, "D0", "D1");
  const physics::Train train = data::default_train();
  const dp::SectionEngine held(train, route, coarse(true));
  const dp::SectionEngine grid(train, route, coarse(false));
  const double target_s = held.min_time_run().running_time_s * 1.12;
  const dp::TimeSearchResult h = dp::solve_for_time(held, target_s, {});
  const dp::TimeSearchResult g = dp::solve_for_time(grid, target_s, {});
  ASSERT_TRUE(h.converged && g.converged);
  EXPECT_NEAR(h.run.sim.running_time_s, target_s, 1e-3);
  const double e_h = h.run.sim.energy.traction_work_J, e_g = g.run.sim.energy.traction_work_J;
  EXPECT_LE(e_h, e_g * (1.0 + 5e-4)) << e_h << " J held against " << e_g << " J grid";
  // No hold brakes below the limit anywhere on the held run.
  for (std::size_t k = 1; k < h.run.sim.trace.size(); ++k) {
    const physics::TracePoint& p = h.run.sim.trace[k];
    if (p.regime != physics::Regime::PartialBrake) continue;
    EXPECT_GE(p.v_ms, physics::speed_from_e(held.envelope().e_at(p.s_m)) - 0.2) << p.s_m;
  }
}

TEST(CruisePolish, ShortCruisesAndDisabledPolishAreLeftAlone) {
  const physics::Train train = data::default_train();
  const physics::Route route = long_level_route();
  const dp::SectionEngine held(train, route, coarse(true));
  const double target_s = held.min_time_run().running_time_s * 1.12;
  dp::TimeSearchOptions off;
  off.cruise_polish.enabled = false;
  const dp::TimeSearchResult plain = dp::solve_for_time(held, target_s, off);
  EXPECT_FALSE(plain.cruise_polish.applied);
  EXPECT_EQ(plain.cruise_polish.simulations, 0);
  dp::TimeSearchOptions long_only;
  long_only.cruise_polish.min_cruise_m = 1e6;  // no cruise is that long
  const dp::TimeSearchResult same = dp::solve_for_time(held, target_s, long_only);
  EXPECT_FALSE(same.cruise_polish.applied);
  EXPECT_EQ(same.run.cost_J, plain.run.cost_J);
  std::string why;
  dp::TimeSearchOptions bad;
  bad.cruise_polish.search_step_m = 0.0;
  EXPECT_FALSE(bad.IsValid(&why));
  EXPECT_NE(why.find("search_step_m"), std::string::npos);
}

}  // namespace
}  // namespace ecorail
