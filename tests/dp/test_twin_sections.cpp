// Sections over equal track (twins: physics::track_key) share one transition table, and a
// journey runs each twin's price once. A line of many equal stops (a TTOBench track of 20 003
// stops 10 m apart) then costs one table, not one per stop. Sharing must change nothing: the
// journey is bit for bit the one with every engine building its own table (a streaming library,
// which keeps no table), and its optimum is the symmetric one that convexity gives.
#include <gtest/gtest.h>

#include <vector>

#include "data/train_io.hpp"
#include "dp/journey.hpp"
#include "dp/section_library.hpp"
#include "dp/time_target.hpp"
#include "physics/route.hpp"
#include "tests/dp/coarse_library.hpp"

namespace ecorail {
namespace {

dp::SectionLibraryOptions coarse(double budget_bytes) {
  return dp::test::coarse_library(5.0, budget_bytes);
}

physics::Route level(double length_m, double gradient_permille, int index) {
  physics::RouteSegment s;
  s.start_m = 0.0;
  s.end_m = length_m;
  s.gradient_permille = gradient_permille;
  s.speed_limit_ms = 60.0 / 3.6;
  return physics::Route({s}, 400.0 * index, 1, "S" + std::to_string(index),
                        "S" + std::to_string(index + 1));
}

TEST(TwinSections, ShareOneTableAndRunBitForBitAsOwnTables) {
  const physics::Train train = data::default_train();
  // A, B, A, B, A: two tracks; names and kilometre posts differ, which twins ignore.
  std::vector<physics::Route> routes;
  for (int i = 0; i < 5; ++i) routes.push_back(level(400.0, i % 2 == 0 ? 0.0 : 5.0, i));
  const dp::SectionLibrary shared(train, routes, coarse(0.0));
  const dp::SectionLibrary own(train, routes, coarse(1.0));  // streams: no table is kept
  ASSERT_FALSE(shared.streams_tables());
  ASSERT_TRUE(own.streams_tables());
  for (std::size_t i = 0; i < routes.size(); ++i) {
    EXPECT_EQ(shared.twin(i), i % 2) << i;
    EXPECT_EQ(&shared.engine(i).transitions(), &shared.engine(i % 2).transitions()) << i;
  }
  EXPECT_NE(&shared.engine(0).transitions(), &shared.engine(1).transitions());
  // The table of two equal tracks is counted once in the estimate.
  const dp::SectionLibrary one_each(train, {routes[0], routes[1]}, coarse(0.0));
  EXPECT_EQ(shared.tables_estimate_bytes(), one_each.tables_estimate_bytes());

  dp::JourneyOptions options;
  options.engine = coarse(0.0).engine;
  const std::vector<double> dwells(4, 20.0);
  const dp::JourneySolution a = dp::solve_journey(shared, 0, 5, dwells, 260.0, options);
  const dp::JourneySolution b = dp::solve_journey(own, 0, 5, dwells, 260.0, options);
  ASSERT_TRUE(a.summary.IsSolutionUsable()) << a.summary.BriefReport();
  ASSERT_TRUE(b.summary.IsSolutionUsable());
  EXPECT_EQ(a.traction_work_J, b.traction_work_J);
  EXPECT_EQ(a.lambda_J_per_s, b.lambda_J_per_s);
  ASSERT_EQ(a.sections.size(), b.sections.size());
  for (std::size_t i = 0; i < a.sections.size(); ++i) {
    EXPECT_EQ(a.sections[i].run.sim.running_time_s, b.sections[i].run.sim.running_time_s);
    EXPECT_EQ(a.sections[i].run.sim.energy.traction_work_J,
              b.sections[i].run.sim.energy.traction_work_J);
  }
}

TEST(TwinSections, ShareOneFrontierEqualToTheirOwn) {
  // A, B, A: the third section's frontier is the first's, computed once, and equal to the one a
  // library holding only that track computes for itself.
  const physics::Train train = data::default_train();
  std::vector<physics::Route> routes;
  for (int i = 0; i < 3; ++i) routes.push_back(level(400.0, i == 1 ? 5.0 : 0.0, i));
  dp::SectionLibraryOptions options = coarse(0.0);
  options.frontier_span_s = 8.0;
  options.frontier_step_s = 2.0;
  const dp::SectionLibrary shared(train, routes, options);
  const dp::SectionLibrary alone(train, {routes[2]}, options);
  shared.build_frontiers(0, 3, nullptr);
  EXPECT_EQ(shared.frontier_computations(), 2);
  const dp::FrontierCurve& twin = shared.frontier(2);
  const dp::FrontierCurve& own = alone.frontier(0);
  ASSERT_EQ(twin.frontier().points.size(), own.frontier().points.size());
  for (std::size_t k = 0; k < own.frontier().points.size(); ++k) {
    EXPECT_EQ(twin.frontier().points[k].running_time_s, own.frontier().points[k].running_time_s);
    EXPECT_EQ(twin.frontier().points[k].cost_J, own.frontier().points[k].cost_J);
  }
}

TEST(TwinSections, EqualStopsTakeTheSymmetricOptimum) {
  // Four equal sections: their frontiers are one convex curve, so the optimal split gives each
  // a quarter of the time, and the journey's energy is four times one section's alone at that
  // time, solved by a fresh engine of its own.
  const physics::Train train = data::default_train();
  std::vector<physics::Route> routes;
  for (int i = 0; i < 4; ++i) routes.push_back(level(400.0, 0.0, i));
  const dp::SectionLibrary library(train, routes, coarse(0.0));
  dp::JourneyOptions options;
  options.engine = coarse(0.0).engine;
  const double total_s = 4 * 48.0;
  const dp::JourneySolution j =
      dp::solve_journey(library, 0, 4, std::vector<double>(3, 20.0), total_s, options);
  ASSERT_TRUE(j.summary.IsSolutionUsable()) << j.summary.BriefReport();
  EXPECT_NEAR(j.running_time_s, total_s, 1e-3);

  const dp::SectionEngine alone(train, level(400.0, 0.0, 9), coarse(0.0).engine);
  const dp::TimeSearchResult quarter = dp::solve_for_time(alone, total_s / 4, options.search);
  ASSERT_TRUE(quarter.converged);
  const double four = 4.0 * alone.energy_cost_J(quarter.run.sim);
  double journey_cost = 0.0;
  for (const auto& s : j.sections) journey_cost += library.engine(0).energy_cost_J(s.run.sim);
  // The journey is an optimum over splits, the equal split one of them: never dearer than it
  // beyond the grid's noise, and by convexity not cheaper either.
  EXPECT_NEAR(journey_cost, four, 2e-3 * four);
}

}  // namespace
}  // namespace ecorail
