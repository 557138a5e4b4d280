// The exact allocation against a brute-force scan of the split, on synthetic convex frontiers
// (E = a / (t - c) + e0, whose optimum is also known in closed form) and at its bounds.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "recovery/allocation.hpp"

namespace ecorail::recovery {
namespace {

// A frontier sampled from E(t) = a / (t - c) + e0 at 0.5 s steps over [t0, t0 + span].
dp::FrontierCurve synthetic(double a, double c, double e0, double t0, double span) {
  dp::Frontier f;
  f.min_time_s = 0.0;  // not the first point: no root zone
  for (double t = t0; t <= t0 + span + 1e-9; t += 0.5) {
    dp::FrontierPoint p;
    p.target_time_s = p.running_time_s = t;
    p.cost_J = p.traction_work_J = a / (t - c) + e0;
    p.converged = true;
    f.points.push_back(p);
  }
  return dp::FrontierCurve(f);
}

TEST(Allocation, EqualMarginalsMatchABruteForceScanOfTheSplit) {
  const dp::FrontierCurve c1 = synthetic(4.0e6, 60.0, 2.0e7, 85.0, 40.0);
  const dp::FrontierCurve c2 = synthetic(9.0e6, 50.0, 1.0e7, 95.0, 40.0);
  const dp::FrontierCurve c3 = synthetic(2.0e6, 70.0, 3.0e7, 80.0, 40.0);
  const std::vector<AllocationItem> items = {
      {&c1, 85.0, 125.0}, {&c2, 95.0, 135.0}, {&c3, 80.0, 120.0}};
  const double total = 300.0;
  const AllocationResult r = allocate_time(items, total);
  ASSERT_TRUE(r.summary.IsSolutionUsable()) << r.summary.FullReport();
  EXPECT_NEAR(r.times_s[0] + r.times_s[1] + r.times_s[2], total, 1e-6);
  // Equal marginals (no section at a bound here).
  EXPECT_EQ(r.summary.at_lower + r.summary.at_upper, 0);
  EXPECT_NEAR(r.marginals_J_per_s[0], r.marginals_J_per_s[1], 1e-3 * r.marginals_J_per_s[0]);
  EXPECT_NEAR(r.marginals_J_per_s[1], r.marginals_J_per_s[2], 1e-3 * r.marginals_J_per_s[0]);
  // Brute force: every split on a 0.02 s grid.
  double best = std::numeric_limits<double>::infinity(), b1 = 0, b2 = 0;
  for (double t1 = 85.0; t1 <= 125.0; t1 += 0.02)
    for (double t2 = 95.0; t2 <= 135.0; t2 += 0.02) {
      const double t3 = total - t1 - t2;
      if (t3 < 80.0 || t3 > 120.0) continue;
      const double e = c1.energy_at(t1) + c2.energy_at(t2) + c3.energy_at(t3);
      if (e < best) best = e, b1 = t1, b2 = t2;
    }
  EXPECT_LE(r.summary.energy_J, best + 1e-6 * best);
  EXPECT_NEAR(r.times_s[0], b1, 0.05);
  EXPECT_NEAR(r.times_s[1], b2, 0.05);
}

TEST(Allocation, BoundsAreKeptAndAnImpossibleTotalFails) {
  const dp::FrontierCurve c1 = synthetic(4.0e6, 60.0, 2.0e7, 85.0, 40.0);
  const dp::FrontierCurve c2 = synthetic(9.0e6, 50.0, 1.0e7, 95.0, 40.0);
  // A lower bound that binds: section 2 may not run below 120 s.
  const AllocationResult r = allocate_time({{&c1, 85.0, 125.0}, {&c2, 120.0, 135.0}}, 220.0);
  ASSERT_TRUE(r.summary.IsSolutionUsable());
  EXPECT_NEAR(r.times_s[1], 120.0, 1e-9);
  EXPECT_NEAR(r.times_s[0], 100.0, 1e-6);
  EXPECT_EQ(r.summary.at_lower, 1);
  // Below the sum of the lower bounds: no allocation.
  const AllocationResult none = allocate_time({{&c1, 85.0, 125.0}, {&c2, 95.0, 135.0}}, 170.0);
  EXPECT_EQ(none.summary.termination, dp::Termination::FAILURE);
  EXPECT_FALSE(none.summary.message.empty());
  // Above the sum of the upper bounds: everything at its upper bound, arriving early.
  const AllocationResult early = allocate_time({{&c1, 85.0, 100.0}, {&c2, 95.0, 110.0}}, 230.0);
  ASSERT_TRUE(early.summary.IsSolutionUsable());
  EXPECT_NEAR(early.times_s[0], 100.0, 1e-9);
  EXPECT_NEAR(early.times_s[1], 110.0, 1e-9);
  EXPECT_NEAR(early.summary.time_left_s, 20.0, 1e-9);
}

TEST(Allocation, OptionsAndItemsAreChecked) {
  const dp::FrontierCurve c1 = synthetic(4.0e6, 60.0, 2.0e7, 85.0, 40.0);
  AllocationOptions o;
  o.time_tolerance_s = 0.0;
  std::string why;
  EXPECT_FALSE(o.IsValid(&why));
  EXPECT_NE(why.find("time_tolerance_s"), std::string::npos);
  EXPECT_THROW(allocate_time({{&c1, 85.0, 125.0}}, 100.0, o), std::invalid_argument);
  EXPECT_THROW(allocate_time({{&c1, 80.0, 125.0}}, 100.0), std::invalid_argument);  // below t_min
  EXPECT_THROW(allocate_time({{nullptr, 85.0, 125.0}}, 100.0), std::invalid_argument);
}

}  // namespace
}  // namespace ecorail::recovery
