// Efficiency maps in the physics and the DP (physics/train.hpp EfficiencyMap): a map that is
// the same number everywhere gives the same energies as that constant (a second path to the
// same figures), and a map that makes high speeds dear moves the optimum: the DP's run under
// the map draws less energy than the constant-efficiency optimum driven by the same train
// (same motion, same running time), measured under the map.
#include <gtest/gtest.h>

#include <cmath>

#include "data/train_io.hpp"
#include "dp/section_engine.hpp"
#include "dp/time_target.hpp"
#include "physics/units.hpp"

namespace ecorail {
namespace {

physics::Route level_route() {
  physics::RouteSegment seg;
  seg.start_m = 0.0;
  seg.end_m = 1500.0;
  seg.speed_limit_ms = units::kmh_to_ms(80.0);
  return physics::Route({seg}, 0.0, 1, "M0", "M1");
}

physics::EfficiencyMap map_over_speed(double at_rest, double at_80_kmh) {
  physics::EfficiencyMap m;
  m.speeds_ms = {0.0, units::kmh_to_ms(80.0)};
  m.forces_N = {0.0, 400e3};
  m.values = {at_rest, at_rest, at_80_kmh, at_80_kmh};
  return m;
}

dp::EngineOptions coarse() {
  dp::EngineOptions o;
  o.grid.ds_m = 10.0;
  o.grid.dv_kmh = 0.5;
  o.grid.substep_m = 5.0;
  return o;
}

TEST(EfficiencyMapDp, AFlatMapEqualsItsConstant) {
  physics::Train constant = data::default_train();
  constant.traction_efficiency = 0.85;
  constant.regen_efficiency = 0.8;
  physics::Train mapped = constant;
  mapped.traction_efficiency_map = map_over_speed(0.85, 0.85);
  mapped.regen_efficiency_map = map_over_speed(0.8, 0.8);
  const physics::Route route = level_route();
  const dp::SectionEngine a(constant, route, coarse());
  const dp::SectionEngine b(mapped, route, coarse());
  const double target = a.min_time_run().running_time_s * 1.2;
  const dp::TimeSearchResult ra = dp::solve_for_time(a, target, {});
  const dp::TimeSearchResult rb = dp::solve_for_time(b, target, {});
  ASSERT_TRUE(ra.converged && rb.converged);
  EXPECT_NEAR(rb.run.sim.energy.traction_input_J, ra.run.sim.energy.traction_input_J,
              1e-9 * ra.run.sim.energy.traction_input_J);
  EXPECT_NEAR(rb.run.sim.energy.regen_J, ra.run.sim.energy.regen_J,
              1e-9 * ra.run.sim.energy.regen_J);
  // Input = work / 0.85 and regen = 0.8 braking, summed step by step.
  EXPECT_NEAR(rb.run.sim.energy.traction_input_J, rb.run.sim.energy.traction_work_J / 0.85,
              1e-9 * rb.run.sim.energy.traction_input_J);
  EXPECT_NEAR(rb.run.sim.energy.regen_J, 0.8 * rb.run.sim.energy.brake_work_J,
              1e-9 * rb.run.sim.energy.regen_J);
}

TEST(EfficiencyMapDp, TheOptimumUnderAMapBeatsTheConstantOptimumDrivenUnderIt) {
  physics::Train constant = data::default_train();
  constant.traction_efficiency = 0.9;
  physics::Train mapped = constant;
  mapped.traction_efficiency_map = map_over_speed(0.95, 0.45);  // high speed is dear
  const physics::Route route = level_route();
  const dp::SectionEngine plain(constant, route, coarse());
  const dp::SectionEngine engine(mapped, route, coarse());
  const double target = plain.min_time_run().running_time_s * 1.15;
  const dp::TimeSearchResult best = dp::solve_for_time(engine, target, {});
  const dp::TimeSearchResult other = dp::solve_for_time(plain, target, {});
  ASSERT_TRUE(best.converged && other.converged);
  // The constant optimum's control on the mapped train: the same motion (efficiencies do not
  // move the train), measured under the map.
  const physics::SimulationResult driven = engine.simulate(other.run.program);
  EXPECT_NEAR(driven.running_time_s, other.run.sim.running_time_s, 1e-9);
  EXPECT_EQ(driven.energy.traction_work_J, other.run.sim.energy.traction_work_J);
  // Input energy measured substep by substep: between work / 0.95 and work / 0.45.
  EXPECT_GT(driven.energy.traction_input_J, driven.energy.traction_work_J / 0.95);
  EXPECT_LT(driven.energy.traction_input_J, driven.energy.traction_work_J / 0.45);
  const double e_best = best.run.sim.energy.traction_input_J;
  const double e_other = driven.energy.traction_input_J;
  EXPECT_NEAR(best.run.sim.running_time_s, target, 1e-3);
  EXPECT_LT(e_best, e_other * (1.0 - 1e-3)) << e_best << " J against " << e_other << " J";
}

}  // namespace
}  // namespace ecorail
