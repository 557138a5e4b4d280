// The periodic-regime analysis (fleet/periodic_regimes.hpp) against direct evaluation of long
// periodic timetables: a regime's steady value per period must be the growth of the used energy
// per period inserted, and the regime start must be a timetable of the problem whose DP value
// the blocks it is made of add up to.
#include <gtest/gtest.h>

#include <cmath>

#include "fleet/headway_optimiser.hpp"
#include "fleet/periodic_regimes.hpp"
#include "fleet/regime_start.hpp"
#include "fleet_fixture.hpp"

namespace ecorail::fleet {
namespace {

TestFleet small_model(double step_s) {
  EnergyModelOptions o;
  o.time_step_s = step_s;
  return TestFleet(testing::small_pattern().trip, testing::small_fleet(10, 60, 200, 9 * 120), o);
}

// Long timetables of P + 1 and P + 7 periods, evaluated whole: their difference is six periods
// of the steady regime, for constants and alternating pairs, resonant or not.
TEST(PeriodicRegimes, SteadyValueIsTheGrowthOfLongTimetables) {
  const TestFleet fleet = small_model(1.0);
  const energy::FleetEnergyModel& m = fleet.model();
  int positive = 0;
  for (auto [a, b] : {std::pair{60, 60}, {90, 90}, {70, 110}, {100, 140}, {150, 200}, {63, 97}}) {
    const double per_period = steady_used_per_period_J(m, a, b);
    const int p = base_periods(m, a, b) + 1;
    const double growth =
        periodic_timetable_used_J(m, a, b, p + 6) - periodic_timetable_used_J(m, a, b, p);
    EXPECT_NEAR(6.0 * per_period, growth, 1e-6 * std::fabs(growth) + 1.0) << a << "/" << b;
    positive += per_period > 0.0;
  }
  EXPECT_GT(positive, 0);  // some regime uses regenerated energy at all
}

// The analysis lists every grid pair within the spread, each valued as above.
TEST(PeriodicRegimes, AnalysisListsTheGridAndItsValues) {
  const TestFleet fleet = small_model(1.0);
  PeriodicRegimeOptions o;
  o.lo_s = 60;
  o.hi_s = 100;
  o.grid_s = 20;
  o.max_spread_s = 20;
  const std::vector<PeriodicRegime> r = analyse_periodic_regimes(fleet.model(), o);
  ASSERT_EQ(r.size(), 5u);  // 60/60 60/80 80/80 80/100 100/100
  EXPECT_EQ(r[1].a_s, 60);
  EXPECT_EQ(r[1].b_s, 80);
  for (const PeriodicRegime& g : r)
    EXPECT_DOUBLE_EQ(g.used_per_period_J, steady_used_per_period_J(fleet.model(), g.a_s, g.b_s));
}

// Refinement to whole seconds: the best regime (a hill climb from the grid's best) is a local
// maximum: no one-second step of it, independently priced, is better.
TEST(PeriodicRegimes, RefinedRegimesAreLocalMaxima) {
  const TestFleet fleet = small_model(1.0);
  const energy::FleetEnergyModel& m = fleet.model();
  PeriodicRegimeOptions o;
  o.lo_s = 60;
  o.hi_s = 140;
  o.grid_s = 20;
  o.max_spread_s = 40;
  const std::vector<PeriodicRegime> grid = analyse_periodic_regimes(m, o);
  const std::vector<PeriodicRegime> refined = refine_regimes(m, grid, o.lo_s, o.hi_s, 2, 2);
  ASSERT_GT(refined.size(), grid.size());
  double best = refined.front().used_per_period_J;
  const PeriodicRegime* top = &refined.front();
  for (const PeriodicRegime& r : refined)
    if (r.used_per_period_J > best) best = r.used_per_period_J, top = &r;
  for (auto [da, db] : {std::pair{-1, 0}, {1, 0}, {0, -1}, {0, 1}, {-1, -1}, {1, 1}}) {
    const int a = top->a_s + da, b = top->b_s + db;
    if (a < o.lo_s || b > o.hi_s || a > b || (top->a_s == top->b_s && da != db)) continue;
    EXPECT_LE(steady_used_per_period_J(m, a, b), top->used_per_period_J) << a << "/" << b;
  }
}

// The regime DP on hand-made values: a resonant pair worth more than its constants is used to
// fill the span, and the result keeps the problem's rules and adds up to the DP's value.
TEST(RegimeStart, FillsTheSpanWithTheBestBlocks) {
  const FleetProblem p = testing::small_fleet(9, 100, 200, 4 * 130 + 4 * 150);
  std::vector<PeriodicRegime> off;
  for (int a = 100; a <= 200; a += 10)
    for (int b = a; b <= 200 && b - a <= 60; b += 10) {
      const double v =
          (a == 130 && b == 150) ? 300.0 : (a == b ? 2.0 * (a == 140 ? 120.0 : 100.0) : 150.0);
      off.push_back({a, b, v});
    }
  const RegimeStart r = regime_start_from(p, 10, off, {});
  ASSERT_FALSE(r.departures_s.empty());
  EXPECT_EQ(departures_problem(p, r.departures_s), "");
  const std::vector<int> h = headways_from_departures(r.departures_s);
  int resonant = 0;
  for (int x : h) resonant += x == 130 || x == 150;
  EXPECT_EQ(resonant, 8);  // four 130/150 pairs, 150 J a headway, beat 140 s at 120 J
  EXPECT_DOUBLE_EQ(r.predicted_used_J, 4 * 300.0);
}

// A start exists whatever the span and the windows' edges: they need not fall on the analysis
// grid (a peak window moved by 3 s once lost the start, and the 2.2 day 3 % of its used energy).
TEST(RegimeStart, WindowsOffTheAnalysisGridStillGetAStart) {
  FleetProblem p = testing::small_fleet(14, 80, 200, 1601);
  p.peak_windows = {{403, 707}};
  p.peak_headway_min_s = 60;
  p.peak_headway_max_s = 70;
  std::string why;
  ASSERT_TRUE(p.IsValid(&why)) << why;
  EnergyModelOptions o;
  o.time_step_s = 1.0;
  const TestFleet fleet(testing::small_pattern().trip, p, o);
  EXPECT_EQ(regime_grid_s(p.headway_min_s, p.headway_max_s), 10);
  EXPECT_EQ(regime_grid_s(p.peak_headway_min_s, p.peak_headway_max_s), 10);
  EXPECT_EQ(regime_grid_s(120, 126), 3);  // a narrow class is still sampled
  EXPECT_EQ(regime_grid_s(120, 120), 1);
  const RegimeStart r = build_regime_start(fleet.model(), p, 2);
  ASSERT_FALSE(r.departures_s.empty());
  EXPECT_EQ(departures_problem(p, r.departures_s), "");
  EXPECT_EQ(r.departures_s.back(), 1601);
  // Its reported used energy is its timetable's, and the reordering never lost any.
  EXPECT_NEAR(r.arranged_used_J, fleet.evaluate(r.departures_s).total.used_regen_J, 1e-6);
  EXPECT_GE(r.arranged_used_J, r.dp_used_J);
}

// A start that runs out of time is dropped, not half built: with `stop` true from the outset
// there is no start; with `stop` true from the DP on (its analyses done) neither.
TEST(RegimeStart, StoppedStartIsDropped) {
  FleetProblem p = testing::small_fleet(14, 80, 200, 1601);
  p.peak_windows = {{403, 707}};
  p.peak_headway_min_s = 60;
  p.peak_headway_max_s = 70;
  EnergyModelOptions o;
  o.time_step_s = 1.0;
  const TestFleet fleet(testing::small_pattern().trip, p, o);
  EXPECT_TRUE(
      build_regime_start(fleet.model(), p, 2, nullptr, [] { return true; }).departures_s.empty());
  const RegimeStart whole = build_regime_start(fleet.model(), p, 2);
  ASSERT_FALSE(whole.departures_s.empty());
  const RegimeStart cut =
      regime_start_from(p, 1, whole.offpeak, whole.peak, 16, [] { return true; });
  EXPECT_TRUE(cut.departures_s.empty());
}

// One headway class: where the bound's relaxation gives no start (the core, from 120 s on the
// 480 s trip, cannot hold the span: more than four trains share the line) the search starts from
// the periodic regimes, and its result uses at least what that start uses; where the
// relaxation gives one (every headway may lie in the core), from both.
TEST(RegimeStart, OneClassGetsItBesideTheRelaxationsStart) {
  EnergyModelOptions o;
  o.time_step_s = 1.0;
  HeadwayOptimiserOptions opt;
  opt.moves_per_run = 4000;
  opt.threads = 2;
  {
    const FleetProblem dense = testing::small_fleet(16, 40, 200, 15 * 75);
    const TestFleet fleet(testing::small_pattern().trip, dense, o);
    const HeadwayOptimiserResult r = optimise_headways(fleet, opt);
    EXPECT_NE(r.summary.method.find("periodic regimes"), std::string::npos) << r.summary.method;
    EXPECT_EQ(r.summary.method.find("the bound's relaxation"), std::string::npos);
    const auto coarse = fleet.model().on_grid(opt.anneal_step_s);
    const RegimeStart start = build_regime_start(*coarse, dense, 2, &fleet.model());
    ASSERT_FALSE(start.departures_s.empty());
    EXPECT_GE(r.summary.used_regen_J, start.arranged_used_J * (1 - 1e-12));
    EXPECT_EQ(departures_problem(dense, departures_from_headways(r.headways_s)), "");
  }
  {
    const FleetProblem sparse = testing::small_fleet(8, 100, 160, 7 * 150);
    const TestFleet fleet(testing::small_pattern().trip, sparse, o);
    const HeadwayOptimiserResult r = optimise_headways(fleet, opt);
    EXPECT_NE(r.summary.method.find("the bound's relaxation"), std::string::npos)
        << r.summary.method;
    EXPECT_NE(r.summary.method.find("periodic regimes"), std::string::npos);
  }
}

}  // namespace
}  // namespace ecorail::fleet
