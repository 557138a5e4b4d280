// Held cruises checked against the grid's own (dp::solve_for_time, dp/time_target.hpp): a run of
// phases that only looks like a saw tooth can cost more held than as the grid has it, and then
// the time is searched again on the grid's own cruises and the cheaper run kept. On TTOBench's
// CH_Fribourg_Bern (data/ttobench/, an unmodified copy) with the FLIRT at its minimum time
// + 10 %, the held runs alone cost 3.8 % more at 5 m x 0.1 km/h than at 5 m x 0.2 km/h (339 979.9
// against 327 570.5 kJ of traction work): a finer grid gave a dearer run. The check is
// independent of the search: the finer grid's run may not cost more than the coarser one's, and
// the run returned may not cost more than the one searched on the grid's own cruises alone.
// About 15 s: three searches of a 31 km run.
#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <string>

#include "data/route_builder.hpp"
#include "data/ttobench_io.hpp"
#include "dp/section_engine.hpp"
#include "dp/time_target.hpp"

namespace ecorail {
namespace {

std::string read_file(const std::string& file) {
  std::ifstream in(file);
  EXPECT_TRUE(in) << file;
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

dp::EngineOptions at_grid(double ds_m, double dv_kmh) {
  dp::EngineOptions o;
  o.grid.ds_m = ds_m;
  o.grid.dv_kmh = dv_kmh;
  o.grid.substep_m = 0.5 * ds_m;  // as `solve` sets it
  return o;
}

TEST(GridCruises, AFinerGridIsNoDearerWhereHeldCruisesCostMore) {
  const std::string track = ECORAIL_SOURCE_DIR "/data/ttobench/CH_Fribourg_Bern.json";
  const std::string flirt = ECORAIL_SOURCE_DIR "/data/ttobench/CH_Stadler_FLIRT_TPF.json";
  const data::Line line = data::line_from_ttobench(read_file(track), track);
  const physics::Train train = data::train_from_ttobench(read_file(flirt), flirt);
  const physics::Route route = data::build_route(line, "S0", "S1", train);
  const double target_s = 1217.506;  // the minimum time + 10 % (docs/ttobench.md)

  const dp::SectionEngine coarse(train, route, at_grid(5.0, 0.2));
  const dp::SectionEngine fine(train, route, at_grid(5.0, 0.1));
  const dp::TimeSearchResult a = dp::solve_for_time(coarse, target_s, {});
  const dp::TimeSearchResult b = dp::solve_for_time(fine, target_s, {});
  ASSERT_TRUE(a.converged && b.converged);
  EXPECT_NEAR(a.run.sim.running_time_s, target_s, 0.01);
  EXPECT_NEAR(b.run.sim.running_time_s, target_s, 0.01);
  // The converged run cost more held than the grid's at its price, so the grid's own were searched.
  EXPECT_GT(b.held_excess_share, dp::kGridCruisesCheckShare);
  EXPECT_TRUE(b.grid_cruises_searched);
  // Grid convergence: the finer grid's run is no dearer (to 0.01 %).
  EXPECT_LE(b.run.cost_J, a.run.cost_J * (1.0 + 1e-4))
      << "5 m x 0.1 km/h: " << b.run.cost_J / 1e3 << " kJ, 5 m x 0.2 km/h: " << a.run.cost_J / 1e3
      << " kJ";
  // And the run returned is no dearer than the search on the grid's own cruises alone.
  const dp::SectionEngine grid_only(fine, dp::SectionEngine::GridCruises{});
  EXPECT_FALSE(grid_only.options().cruise_as_hold);
  const dp::TimeSearchResult g = dp::solve_for_time(grid_only, target_s, {});
  ASSERT_TRUE(g.converged);
  EXPECT_LE(b.run.cost_J, g.run.cost_J * (1.0 + 1e-9));
}

}  // namespace
}  // namespace ecorail
