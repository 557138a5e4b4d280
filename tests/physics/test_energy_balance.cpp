// The energy balance checked before any result is reported: traction - braking =
// resistance work (Davis, gradient, curve) + kinetic change, integrated over the trace
// independently of the simulator's ledger, with non-negative dissipation. A reference run
// closes it far inside the tolerance; a ledger off by 1 % does not; and a train with a negative
// Davis coefficient, which loaders refuse but a library caller can still build, would
// regenerate 77 times its traction energy: such a run is never usable.
#include <gtest/gtest.h>

#include <cmath>

#include "data/line_loader.hpp"
#include "data/route_builder.hpp"
#include "data/train_io.hpp"
#include "dp/section_engine.hpp"
#include "dp/section_solve.hpp"
#include "physics/energy_balance.hpp"

namespace ecorail {
namespace {

struct ReferenceSection {
  physics::Train train = data::default_train();
  physics::Route route = data::build_route(data::default_line(), "A6", "A7", train);
};

dp::EngineOptions coarse() {
  dp::EngineOptions o;
  o.grid = {20.0, 1.0, 10.0};
  return o;
}

TEST(EnergyBalance, TheFlatOutRunClosesFarInsideTheTolerance) {
  const ReferenceSection s;
  const dp::SectionEngine engine(s.train, s.route, coarse());
  const physics::SimulationResult& run = engine.min_time_run();
  const physics::EnergyBalance b = physics::energy_balance(engine.motion(), run);
  EXPECT_TRUE(b.closes());
  EXPECT_GT(b.traction_work_J, 1e7);
  EXPECT_GT(b.dissipation_J, 0.0);
  // Ends at rest from rest: all the work went into resistance and braking.
  EXPECT_NEAR(b.kinetic_change_J, 0.0, 1e3);
  EXPECT_LT(std::abs(b.residual_J), 1e-3 * b.traction_work_J) << b.residual_J;
}

TEST(EnergyBalance, ALedgerOffByOnePercentDoesNotClose) {
  const ReferenceSection s;
  const dp::SectionEngine engine(s.train, s.route, coarse());
  physics::SimulationResult run = engine.min_time_run();
  run.energy.traction_work_J *= 1.01;
  EXPECT_FALSE(physics::energy_balance(engine.motion(), run).closes());
}

TEST(EnergyBalance, ANegativeDavisCoefficientIsNeverAUsableResult) {
  ReferenceSection s;
  s.train.davis.A = -50.0;  // past the loader's range: resistance pushes the train
  dp::SectionSolveOptions options;
  options.engine = coarse();
  const dp::SectionSolution sol = dp::solve_section(s.train, s.route, 110.0, options);
  const physics::EnergyBalance b =
      physics::energy_balance(dp::SectionEngine(s.train, s.route, coarse()).motion(), sol.run.sim);
  EXPECT_LT(b.dissipation_J, 0.0);
  EXPECT_FALSE(b.closes());
  EXPECT_FALSE(sol.summary.IsSolutionUsable()) << sol.summary.BriefReport();
}

}  // namespace
}  // namespace ecorail
