// The exact refinement near a headway sequence (energy/window_refine.hpp) on the small pattern
// (trip 480 s, so the core starts at 120 s): its window terms sum to the used energy of the
// model's balance on every core timetable; one pass finds the best sequence of its neighbourhood
// (each headway within max_step_s, the span kept), checked against a brute force over every such
// sequence; more passes never lose; one and two threads agree; a headway below the core makes it
// not applicable. The headway optimiser's result never loses by it.
#include <gtest/gtest.h>

#include <algorithm>
#include <functional>
#include <numeric>

#include "../fleet/fleet_fixture.hpp"
#include "energy/window_refine.hpp"
#include "energy/window_terms.hpp"

namespace ecorail::fleet {
namespace {

using energy::window_refine;
using energy::WindowRefineOptions;
using energy::WindowRefineSummary;

// Every sequence within +-d of h, each in [lo, hi], with the same sum.
void for_each_neighbour(const std::vector<int>& h, int d, int lo, int hi,
                        const std::function<void(const std::vector<int>&)>& f) {
  std::vector<int> x(h.size());
  std::function<void(std::size_t, int)> rec = [&](std::size_t k, int change) {
    if (k == h.size()) {
      if (change == 0) f(x);
      return;
    }
    for (int c = -d; c <= d; ++c) {
      x[k] = h[k] + c;
      if (x[k] >= lo && x[k] <= hi) rec(k + 1, change + c);
    }
  };
  rec(0, 0);
}

TEST(WindowRefine, TheWindowTermsSumToTheUsedEnergyOnTheCore) {
  const FleetProblem p = testing::small_fleet(7, 100, 150, 6 * 130);
  const TestFleet fleet(testing::small_pattern().trip, p, testing::tenth_of_a_second());
  const energy::window_terms::ExactTerms terms(fleet.profile(), fleet.profile().ticks_per_second());
  for (const std::vector<int>& h : {std::vector<int>{130, 130, 130, 130, 130, 130},
                                    {120, 140, 125, 135, 150, 110},
                                    {149, 150, 120, 121, 121, 119},
                                    {123, 137, 131, 129, 127, 133}}) {
    // Every four consecutive headways sum to at least L (about the 480 s trip): no fifth train.
    const int L = energy::window_terms::active_seconds(fleet.profile());
    for (std::size_t j = 0; j + 3 < h.size(); ++j)
      ASSERT_GE(h[j] + h[j + 1] + h[j + 2] + h[j + 3], L);
    const double used = fleet.used_J(h);
    EXPECT_GT(used, 0.0);
    EXPECT_NEAR(terms.value_J(h), used, 1e-9 * used + 1e-6);
  }
}

TEST(WindowRefine, OnePassFindsTheBestSequenceOfItsNeighbourhood) {
  const FleetProblem p = testing::small_fleet(7, 100, 150, 6 * 130);
  const TestFleet fleet(testing::small_pattern().trip, p, testing::tenth_of_a_second());
  // The core of the trip (about 480 s), within the limits.
  const int lo = energy::window_terms::core_min_s(
                energy::window_terms::active_seconds(fleet.profile()), limits_of(p)),
            hi = p.headway_max_s;
  ASSERT_LE(lo, 122);
  int gained = 0;  // cases where the neighbourhood holds a better sequence than the start
  for (const std::vector<int>& start : {std::vector<int>{130, 130, 130, 130, 130, 130},
                                        {122, 141, 126, 134, 135, 122},
                                        {146, 145, 122, 122, 122, 123}}) {
    ASSERT_EQ(std::accumulate(start.begin(), start.end(), 0), p.span_s);
    for (int d : {1, 2}) {
      WindowRefineOptions o;
      o.max_step_s = d;
      o.max_passes = 1;
      const WindowRefineSummary r = window_refine(fleet.profile(), limits_of(p), start, o);
      ASSERT_TRUE(r.applicable) << r.why_not;
      double best = 0.0;
      int neighbours = 0;
      for_each_neighbour(start, d, lo, hi, [&](const std::vector<int>& h) {
        best = std::max(best, fleet.used_J(h));
        ++neighbours;
      });
      EXPECT_GT(neighbours, 10);
      EXPECT_NEAR(r.used_J, best, 1e-9 * best + 1e-6) << "step " << d;
      EXPECT_NEAR(r.used_J, fleet.used_J(r.headways_s), 1e-9 * best + 1e-6);
      EXPECT_NEAR(r.start_used_J, fleet.used_J(start), 1e-9 * best + 1e-6);
      gained += best > r.start_used_J * (1 + 1e-9);
      EXPECT_EQ(std::accumulate(r.headways_s.begin(), r.headways_s.end(), 0), p.span_s);
      for (std::size_t j = 0; j < start.size(); ++j)
        EXPECT_LE(std::abs(r.headways_s[j] - start[j]), d);
    }
  }
  EXPECT_GE(gained, 3) << "the brute force must have something to find";
}

TEST(WindowRefine, MorePassesNeverLoseAndThreadsAgree) {
  const FleetProblem p = testing::small_fleet(12, 100, 150, 11 * 132);
  const TestFleet fleet(testing::small_pattern().trip, p, testing::tenth_of_a_second());
  std::vector<int> start(11, 132);
  WindowRefineOptions one;
  one.max_passes = 1;
  one.threads = 1;
  WindowRefineOptions many = one;
  many.max_passes = 20;
  WindowRefineOptions two = many;
  two.threads = 2;
  const WindowRefineSummary a = window_refine(fleet.profile(), limits_of(p), start, one);
  const WindowRefineSummary b = window_refine(fleet.profile(), limits_of(p), start, many);
  const WindowRefineSummary c = window_refine(fleet.profile(), limits_of(p), start, two);
  ASSERT_TRUE(a.applicable) << a.why_not;
  EXPECT_GE(a.used_J, a.start_used_J);
  EXPECT_GE(b.used_J, a.used_J);
  EXPECT_GT(b.used_J, b.start_used_J) << "the uniform timetable is no local optimum here";
  EXPECT_EQ(b.headways_s, c.headways_s);
  EXPECT_EQ(b.used_J, c.used_J);
  EXPECT_NEAR(b.used_J, fleet.used_J(b.headways_s), 1e-9 * b.used_J + 1e-6);
}

TEST(WindowRefine, AHeadwayBelowTheCoreOrABadSumIsNotRefined) {
  const FleetProblem p = testing::small_fleet(5, 100, 150, 4 * 125);
  const TestFleet fleet(testing::small_pattern().trip, p, testing::tenth_of_a_second());
  const std::vector<int> below{110, 130, 130, 130};
  const WindowRefineSummary r = window_refine(fleet.profile(), limits_of(p), below);
  EXPECT_FALSE(r.applicable);
  EXPECT_NE(r.why_not.find("core"), std::string::npos) << r.why_not;
  EXPECT_EQ(r.headways_s, below);
  const WindowRefineSummary s =
      window_refine(fleet.profile(), limits_of(p), std::vector<int>{125, 125, 125, 126});
  EXPECT_FALSE(s.applicable);
  EXPECT_NE(s.why_not.find("span"), std::string::npos) << s.why_not;
  WindowRefineOptions bad;
  bad.max_step_s = 0;
  std::string why;
  EXPECT_FALSE(bad.IsValid(&why));
  EXPECT_NE(why.find("max_step_s"), std::string::npos);
}

// The optimiser with the refinement never ends worse than without it, on a fleet whose every
// headway lies in the core (from 122 s).
TEST(WindowRefine, TheOptimiserNeverLosesByIt) {
  const FleetProblem p = testing::small_fleet(24, 122, 150, 23 * 134);
  const TestFleet fleet(testing::small_pattern().trip, p, testing::tenth_of_a_second());
  HeadwayOptimiserOptions with;
  with.moves_per_run = 200;
  with.threads = 1;
  HeadwayOptimiserOptions without = with;
  without.exact_refine = false;
  const HeadwayOptimiserResult a = optimise_headways(fleet.model(), p, with);
  const HeadwayOptimiserResult b = optimise_headways(fleet.model(), p, without);
  EXPECT_GE(a.evaluation.total.used_regen_J, b.evaluation.total.used_regen_J * (1 - 1e-12));
  EXPECT_EQ(b.summary.refinements, 0);
  // Here the short annealing leaves the polish where the exact search still gains.
  EXPECT_GE(a.summary.refinements, 1);
  EXPECT_NE(a.summary.method.find("exact refinement"), std::string::npos) << a.summary.method;
}

}  // namespace
}  // namespace ecorail::fleet
