// The exact optimum of a headway range in the core (energy/window_span_optimum.hpp) on the small
// pattern (trip 480 s, the core from about 120 s): it equals a brute force over every timetable
// of the range, priced by the model's own balance; its relaxed bound is never below that
// optimum; an incumbent prunes without changing the answer (the optimum given as incumbent comes
// back unimproved); one and two threads agree; bad input is named; the headway optimiser proves
// its result with it on a fleet whose whole domain is the core.
#include <gtest/gtest.h>

#include <algorithm>
#include <functional>
#include <numeric>

#include "../fleet/fleet_fixture.hpp"
#include "energy/window_span_optimum.hpp"
#include "energy/window_terms.hpp"

namespace ecorail::fleet {
namespace {

using energy::window_span_optimum;
using energy::WindowSpanOptions;
using energy::WindowSpanSummary;

// The best used energy over every sequence of n headways in [lo, hi] summing to span, by the
// model's balance.
std::pair<double, std::vector<int>> brute_force(const TestFleet& fleet, int n, int lo, int hi,
                                                int span) {
  std::vector<int> x(n), best_h;
  double best = -1.0;
  std::function<void(int, int)> rec = [&](int k, int left) {
    if (k == n - 1) {
      if (left < lo || left > hi) return;
      x[k] = left;
      const double v = fleet.used_J(x);
      if (v > best) best = v, best_h = x;
      return;
    }
    for (int h = lo; h <= hi; ++h) {
      const int rest = left - h;
      if (rest < (n - 1 - k) * lo || rest > (n - 1 - k) * hi) continue;
      x[k] = h;
      rec(k + 1, rest);
    }
  };
  rec(0, span);
  return {best, best_h};
}

TEST(WindowSpanOptimum, EqualsTheBruteForceOptimumOfItsRange) {
  int uneven = 0;  // optima that are not the even timetable: the search has something to find
  for (const auto& [trains, span] :
       std::vector<std::pair<int, int>>{{6, 5 * 143}, {7, 6 * 144 + 3}, {7, 6 * 146 + 2}}) {
    const FleetProblem p = testing::small_fleet(trains, 100, 150, span);
    const TestFleet fleet(testing::small_pattern().trip, p, testing::tenth_of_a_second());
    WindowSpanOptions o;
    o.lowest_headway_s = 140;
    const WindowSpanSummary r = window_span_optimum(fleet.profile(), limits_of(p), {}, o);
    ASSERT_TRUE(r.applicable) << r.why_not;
    EXPECT_EQ(r.lowest_headway_s, 140);
    EXPECT_EQ(r.highest_headway_s, 150);
    const auto [best, best_h] = brute_force(fleet, trains - 1, 140, 150, span);
    EXPECT_NEAR(r.used_J, best, 1e-9 * best + 1e-6) << "trains " << trains << " span " << span;
    EXPECT_NEAR(r.used_J, fleet.used_J(r.headways_s), 1e-9 * best + 1e-6);
    EXPECT_EQ(std::accumulate(r.headways_s.begin(), r.headways_s.end(), 0), span);
    EXPECT_GE(r.dual_bound_J, best * (1 - 1e-12)) << "weak duality";
    uneven += *std::min_element(best_h.begin(), best_h.end()) + 1 <
              *std::max_element(best_h.begin(), best_h.end());
    // The optimum as incumbent: nothing better, the same value; a poor incumbent: the optimum.
    const WindowSpanSummary again = window_span_optimum(fleet.profile(), limits_of(p), best_h, o);
    EXPECT_FALSE(again.improved);
    EXPECT_NEAR(again.used_J, best, 1e-9 * best + 1e-6);
    EXPECT_GT(again.pruned_pairs, 0) << "the bound prunes once an incumbent is known";
    std::vector<int> poor(trains - 1, span / (trains - 1));
    poor.back() += span - std::accumulate(poor.begin(), poor.end(), 0);
    const WindowSpanSummary from_poor = window_span_optimum(fleet.profile(), limits_of(p), poor, o);
    EXPECT_NEAR(from_poor.used_J, best, 1e-9 * best + 1e-6);
    EXPECT_EQ(from_poor.improved, from_poor.incumbent_used_J < best * (1 - 1e-9));
  }
  EXPECT_GE(uneven, 2);
}

TEST(WindowSpanOptimum, ThreadsAgree) {
  const FleetProblem p = testing::small_fleet(16, 100, 150, 15 * 137);
  const TestFleet fleet(testing::small_pattern().trip, p, testing::tenth_of_a_second());
  WindowSpanOptions one;
  one.threads = 1;
  WindowSpanOptions two = one;
  two.threads = 2;
  const WindowSpanSummary a = window_span_optimum(fleet.profile(), limits_of(p), {}, one);
  const WindowSpanSummary b = window_span_optimum(fleet.profile(), limits_of(p), {}, two);
  ASSERT_TRUE(a.applicable) << a.why_not;
  EXPECT_EQ(a.headways_s, b.headways_s);
  EXPECT_EQ(a.used_J, b.used_J);
  EXPECT_EQ(a.dual_bound_J, b.dual_bound_J);
  EXPECT_GE(a.dual_bound_J, a.used_J);
  EXPECT_NEAR(a.used_J, fleet.used_J(a.headways_s), 1e-9 * a.used_J + 1e-6);
}

TEST(WindowSpanOptimum, ARangeThatCannotMeetTheSpanOrABadOptionIsNamed) {
  const FleetProblem p = testing::small_fleet(5, 100, 150, 4 * 125);
  const TestFleet fleet(testing::small_pattern().trip, p, testing::tenth_of_a_second());
  WindowSpanOptions o;
  o.lowest_headway_s = 140;  // four headways of at least 140 s exceed the 500 s span
  const WindowSpanSummary r = window_span_optimum(fleet.profile(), limits_of(p), {}, o);
  EXPECT_FALSE(r.applicable);
  EXPECT_NE(r.why_not.find("span"), std::string::npos) << r.why_not;
  EXPECT_NE(r.BriefReport().find("not applicable"), std::string::npos);
  WindowSpanOptions bad;
  bad.max_dual_evaluations = 1;
  std::string why;
  EXPECT_FALSE(bad.IsValid(&why));
  EXPECT_NE(why.find("max_dual_evaluations"), std::string::npos);
  EXPECT_THROW(window_span_optimum(fleet.profile(), limits_of(p), {}, bad), std::invalid_argument);
}

// With a time limit the optimiser runs the exact search after its first round; on a fleet whose
// whole domain is the core (headways from 122 s) its result is then the proven optimum, and the
// summary and the JSON's method say on which timetables.
TEST(WindowSpanOptimum, TheOptimiserProvesItsResultOnTheCore) {
  const FleetProblem p = testing::small_fleet(24, 122, 150, 23 * 134);
  const TestFleet fleet(testing::small_pattern().trip, p, testing::tenth_of_a_second());
  HeadwayOptimiserOptions o;
  o.moves_per_run = 200;
  o.threads = 2;
  o.time_limit_s = 6.0;
  const HeadwayOptimiserResult r = optimise_headways(fleet.model(), p, o);
  ASSERT_EQ(r.summary.exact_part, "every headway in 122-150 s") << r.summary.method;
  const double used = r.evaluation.total.used_regen_J;
  EXPECT_NEAR(used, r.summary.exact_part_used_J, 1e-9 * used + 1e-6);
  const WindowSpanSummary alone = window_span_optimum(fleet.profile(), limits_of(p), {});
  EXPECT_NEAR(used, alone.used_J, 1e-9 * used + 1e-6);
  EXPECT_NE(r.summary.method.find("no timetable with every headway in 122-150 s is better"),
            std::string::npos)
      << r.summary.method;
  EXPECT_NE(r.summary.FullReport().find("no timetable with every headway in 122-150 s"),
            std::string::npos);
  // Without a time limit it does not run (it may take minutes on a full day).
  o.time_limit_s = 0.0;
  EXPECT_TRUE(optimise_headways(fleet.model(), p, o).summary.exact_part.empty());
}

}  // namespace
}  // namespace ecorail::fleet
