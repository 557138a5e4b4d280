// A time limit is one for the whole headway search (polish included) and for the whole pattern
// search (every stage), and a search it stops is NO_CONVERGENCE with its gap stated, never
// CONVERGENCE.
#include <gtest/gtest.h>

#include <cmath>

#include "fleet/search_support.hpp"
#include "fleet_fixture.hpp"

namespace ecorail::fleet {
namespace {

// A limit of a millisecond is over before the annealing's first move (the two-train values and
// the starts take longer): neither the annealing nor the polish may then move a train, so the
// result is one of the starts, and the summary says the limit stopped the search.
TEST(HeadwayOptimiserTimeLimit, StopsThePolishToo) {
  const FleetProblem p = testing::small_fleet(10, 80, 200, 9 * 150);
  EnergyModelOptions o;
  o.time_step_s = 0.1;
  const TestFleet fleet(testing::small_pattern().trip, p, o);
  HeadwayOptimiserOptions opt;
  opt.moves_per_run = 100000;
  opt.time_limit_s = 1e-3;
  const HeadwayOptimiserResult r = optimise_headways(fleet, opt);
  EXPECT_TRUE(r.summary.time_limit_reached);
  EXPECT_EQ(r.summary.moves, 0);
  EXPECT_EQ(r.summary.termination, Termination::NO_CONVERGENCE);
  EXPECT_TRUE(std::isfinite(r.summary.gap_fraction));
  EXPECT_GT(r.summary.gap_fraction, opt.gap_fraction);
  EXPECT_NE(r.summary.message.find("time limit"), std::string::npos);
  EXPECT_NE(r.summary.BriefReport().find("NO_CONVERGENCE"), std::string::npos);
}

// The same search without a limit: CONVERGENCE exactly when the proven gap is within the
// tolerance.
TEST(HeadwayOptimiserTimeLimit, ConvergenceOnlyWithinTheGapTolerance) {
  const FleetProblem p = testing::small_fleet(10, 80, 200, 9 * 150);
  EnergyModelOptions o;
  o.time_step_s = 0.1;
  const TestFleet fleet(testing::small_pattern().trip, p, o);
  HeadwayOptimiserOptions opt;
  opt.moves_per_run = 2000;
  const HeadwayOptimiserResult tight = optimise_headways(fleet, opt);
  ASSERT_GT(tight.summary.gap_fraction, 0.0);
  EXPECT_EQ(tight.summary.termination, tight.summary.gap_fraction <= opt.gap_fraction
                                           ? Termination::CONVERGENCE
                                           : Termination::NO_CONVERGENCE);
  opt.gap_fraction = 0.999;
  const HeadwayOptimiserResult wide = optimise_headways(fleet, opt);
  EXPECT_EQ(wide.headways_s, tight.headways_s);
  EXPECT_EQ(wide.summary.termination, Termination::CONVERGENCE);
}

}  // namespace
}  // namespace ecorail::fleet

namespace ecorail::fleet {
namespace {

// The pattern search keeps one limit for the whole run: the headways for the start pattern,
// the pattern moves, the headways for the pattern found and the per-train stage together,
// with budgets that would take minutes. What no limit can cut short (each headway stage's bound,
// starts and final account) is measured in the same run by the same search with a limit of a
// millisecond, so the margin follows the machine's load; 1 s more covers one pattern move (a
// section re-solve) begun just before the limit.
TEST(PatternSearchTimeLimit, WholeRunKeepsTheLimit) {
  FleetProblem problem = testing::small_fleet(12, 60, 200, 11 * 110);
  problem.trip_time_s = 480.0;  // the small pattern's trip
  EnergyModelOptions model;
  model.time_step_s = 0.1;
  PatternSearchOptions o;
  o.headways.moves_per_run = 50000000;  // minutes of annealing without the limit
  o.per_train_patterns = true;
  const auto& lib = testing::small_library();
  const PatternTrip& start = testing::small_pattern();
  o.headways.time_limit_s = 1e-3;
  auto t0 = SearchClock::now();
  optimise_pattern(lib, problem, model, start, o);
  const double fixed = seconds_since(t0);
  o.headways.time_limit_s = 3.0;
  t0 = SearchClock::now();
  const PatternSearchResult r = optimise_pattern(lib, problem, model, start, o);
  const double wall = seconds_since(t0);
  RecordProperty("wall_s", std::to_string(wall));
  RecordProperty("fixed_s", std::to_string(fixed));
  EXPECT_LE(wall, o.headways.time_limit_s + fixed + 1.0) << "fixed costs " << fixed << " s";
  EXPECT_NE(r.timetable.summary.termination, Termination::CONVERGENCE);
  EXPECT_EQ(departures_problem(problem, r.timetable.evaluation.departures_s), "");
  // The search's own summary says the same, and its full report carries the headway search's.
  EXPECT_EQ(r.termination(), r.timetable.summary.termination);
  EXPECT_NE(r.FullReport().find(r.BriefReport()), std::string::npos);
  EXPECT_NE(r.FullReport().find(r.timetable.summary.FullReport()), std::string::npos);
}

}  // namespace
}  // namespace ecorail::fleet
