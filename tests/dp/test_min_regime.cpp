// A minimum regime length on a solved run (dp::enforce_min_regime): every control phase of the
// result is at least the minimum long in its re-simulation, the run still meets its time and its
// stop, and what it costs is measured against the unmerged optimum (small; never a saving beyond
// the grid's noise). Solve and frontier take one path: a frontier point is the stand-alone solve
// of its time, to the joule.
#include <gtest/gtest.h>

#include <cmath>

#include "data/line_loader.hpp"
#include "data/route_builder.hpp"
#include "data/train_io.hpp"
#include "dp/frontier.hpp"
#include "dp/regimes.hpp"
#include "dp/time_target.hpp"

namespace ecorail {
namespace {

TEST(MinRegime, PhasesReachTheMinimumAndTheTimeIsKept) {
  const physics::Train train = data::default_train();
  // A8 -> A9 in 130 s with the grid's own cruises: holds of 1-3 m between coasts on the
  // descent (the default holds the cruise and polishes it into one hold, with nothing to merge).
  const physics::Route route = data::build_route(data::default_line(), "A8", "A9", train);
  dp::EngineOptions grid_cruises;
  grid_cruises.cruise_as_hold = false;
  const dp::SectionEngine engine(train, route, grid_cruises);
  const dp::TimeSearchResult found = dp::solve_for_time(engine, 130.0, {});
  ASSERT_TRUE(found.converged);

  dp::MinRegimeOptions options;
  options.min_length_m = 20.0;
  const dp::MinRegimeResult m = dp::enforce_min_regime(engine, found.run, 130.0, options);
  EXPECT_GT(m.merged_entries, 0);
  EXPECT_TRUE(m.met);
  EXPECT_NEAR(m.run.sim.running_time_s, 130.0, 0.001);
  EXPECT_EQ(m.short_entries_left, 0);
  // Checked here directly on the program, independently of the function's own count.
  const auto& p = m.run.program;
  for (std::size_t k = 1; k + 1 < p.size(); ++k) {
    EXPECT_GE(p[k + 1].from_m - p[k].from_m, 20.0) << "phase " << k;
  }
  EXPECT_DOUBLE_EQ(m.cost_before_J, engine.energy_cost_J(found.run.sim));
  const double cost = m.cost_after_J / m.cost_before_J - 1.0;
  EXPECT_GT(cost, -1e-3);  // the unmerged run is the optimum up to the grid
  EXPECT_LT(cost, 5e-3);

  dp::MinRegimeOptions none;
  const dp::MinRegimeResult same = dp::enforce_min_regime(engine, found.run, 130.0, none);
  EXPECT_EQ(same.merged_entries, 0);
  EXPECT_EQ(same.run.sim.energy.traction_work_J, found.run.sim.energy.traction_work_J);
}

TEST(MinRegime, FrontierPointsAreTheStandAloneSolves) {
  const physics::Train train = data::default_train();
  const physics::Route route = data::build_route(data::default_line(), "A6", "A7", train);
  const dp::SectionEngine engine(train, route, {});
  dp::FrontierOptions options;
  options.t_min_s = 140.0;
  options.t_max_s = 150.0;
  options.step_s = 5.0;
  const dp::Frontier f = dp::compute_frontier(engine, options);
  ASSERT_EQ(f.points.size(), 3u);
  for (const auto& point : f.points) {
    const dp::TimeSearchResult alone = dp::solve_for_time(engine, point.target_time_s, {});
    EXPECT_EQ(point.traction_work_J, alone.run.sim.energy.traction_work_J) << point.target_time_s;
    EXPECT_EQ(point.running_time_s, alone.run.sim.running_time_s) << point.target_time_s;
  }
}

}  // namespace
}  // namespace ecorail
