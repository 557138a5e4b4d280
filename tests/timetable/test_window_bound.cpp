// The window bound (timetable/window_bound.hpp) on fleets small enough to enumerate every
// timetable: the relaxed value of every timetable is at least its used energy (each window term
// bounds its share), equal to it on the bound's grid when every headway lies in the core (the
// decomposition is exact there), and the bound is never below the brute-force optimum.
#include <gtest/gtest.h>

#include <functional>

#include "fleet_fixture.hpp"
#include "timetable/fleet_models.hpp"
#include "timetable/headway_optimiser.hpp"
#include "timetable/search_starts.hpp"
#include "timetable/window_bound.hpp"

namespace ecorail::timetable {
namespace {

// Every headway sequence of the problem (sum = span, each in range).
void for_each_timetable(const FleetProblem& p,
                        const std::function<void(const std::vector<int>&)>& f) {
  std::vector<int> h(p.trains - 1);
  std::function<void(int, int)> rec = [&](int k, int left) {
    if (k == static_cast<int>(h.size()) - 1) {
      if (left < p.headway_min_s || left > p.headway_max_s) return;
      h[k] = left;
      f(h);
      return;
    }
    for (int x = p.headway_min_s; x <= p.headway_max_s; ++x) {
      h[k] = x;
      rec(k + 1, left - x);
    }
  };
  rec(0, p.span_s);
}

struct Case {
  int trains, hmin, hmax, span;
};

TEST(WindowBound, EveryTimetableBelowItsRelaxedValueAndTheBoundAboveTheOptimum) {
  // The small pattern is active about 480 s, so the core starts near 120 s: headways 80-140
  // cover both the core and the cells below it. Spans chosen so that some timetables are
  // all-core and some are not.
  for (const Case c : {Case{4, 80, 140, 380}, Case{5, 90, 140, 500}, Case{6, 100, 130, 620}}) {
    const FleetProblem p = testing::small_fleet(c.trains, c.hmin, c.hmax, c.span);
    EnergyModelOptions o;
    o.time_step_s = 0.1;
    const FleetModels models(testing::small_pattern().trip, p, o);
    WindowBoundOptions wo;
    wo.short_cell_s = 7;
    const WindowBound bound = window_used_regen_bound(models.profile(), p, wo);
    ASSERT_TRUE(bound.applicable) << bound.why_not;
    auto balance = models.make_balance();
    double best = 0.0;
    int timetables = 0, core = 0;
    std::vector<std::vector<int>> sample;
    std::vector<double> used_of_sample;
    for_each_timetable(p, [&](const std::vector<int>& h) {
      balance->place_all(departures_from_headways(h));
      const double used = to_joules(balance->used());
      best = std::max(best, used);
      ++timetables;
      // Every all-core timetable and every third of the rest.
      if (*std::min_element(h.begin(), h.end()) < bound.core_min_s && timetables % 3 != 0) return;
      sample.push_back(h);
      used_of_sample.push_back(used);
    });
    const std::vector<double> relaxed = window_relaxed_values_J(models.profile(), p, sample, wo);
    for (std::size_t i = 0; i < sample.size(); ++i) {
      const double used = used_of_sample[i];
      EXPECT_GE(relaxed[i], used * (1 - 1e-12)) << c.trains << " trains, timetable " << i;
      if (*std::min_element(sample[i].begin(), sample[i].end()) >= bound.core_min_s) {
        ++core;
        EXPECT_NEAR(relaxed[i], used, 1e-6 * used + 1e-3) << "core timetable: exact decomposition";
      }
    }
    EXPECT_GT(timetables, 10);
    EXPECT_GT(core, 0) << c.trains << " trains: no all-core timetable sampled";
    EXPECT_GT(best, 0.0);
    EXPECT_GE(bound.bound_used_J, best * (1 - 1e-12)) << c.trains << " trains";
  }
}

// The optimiser's certificate with the window bound covers its true shortfall. (On this instance
// the annealing ends 0.017 % of used energy below the brute-force optimum, with any seed tried:
// the search, not the bound, is what issue 23 item 1 still has to improve.)
TEST(WindowBound, TheOptimisersGapWithItCoversItsTrueShortfall) {
  const FleetProblem p = testing::small_fleet(5, 90, 140, 500);
  EnergyModelOptions o;
  o.time_step_s = 0.1;
  const FleetModels models(testing::small_pattern().trip, p, o);
  auto balance = models.make_balance();
  double best = 0.0;
  for_each_timetable(p, [&](const std::vector<int>& h) {
    balance->place_all(departures_from_headways(h));
    best = std::max(best, to_joules(balance->used()));
  });
  HeadwayOptimiserOptions opt;
  opt.moves_per_run = 2000;
  opt.polish_window_s = 60;
  opt.window_bound = true;
  const HeadwayOptimiserResult r = optimise_headways(models, opt);
  EXPECT_LE(r.summary.used_regen_J, best * (1 + 1e-12));
  EXPECT_GE(r.summary.bound_used_regen_J, best * (1 - 1e-12));
  EXPECT_GE(r.summary.gap_fraction * r.summary.substation_J,
            (best - r.summary.used_regen_J) * (1 - 1e-9));
  EXPECT_NE(r.summary.method.find("window bound"), std::string::npos) << r.summary.method;
}

TEST(SearchStarts, RepairKeepsTheRangeReachesTheSpanAndNeverMovesBack) {
  const FleetProblem p = testing::small_fleet(8, 100, 200, 7 * 150);
  std::uint64_t x = 12345;
  for (int trial = 0; trial < 200; ++trial) {
    std::vector<int> h(7);
    long excess = -p.span_s;
    for (int& v : h) {
      x = x * 6364136223846793005ULL + 1442695040888963407ULL;
      v = 100 + static_cast<int>((x >> 33) % 101);
      excess += v;
    }
    const std::vector<int> r = repair_to_span(h, p);
    long sum = 0, moved = 0;
    for (std::size_t k = 0; k < h.size(); ++k) {
      EXPECT_GE(r[k], p.headway_min_s);
      EXPECT_LE(r[k], p.headway_max_s);
      EXPECT_TRUE(excess >= 0 ? r[k] <= h[k] : r[k] >= h[k]);
      sum += r[k];
      moved += std::abs(r[k] - h[k]);
    }
    EXPECT_EQ(sum, p.span_s);
    EXPECT_EQ(moved, std::abs(excess));
  }
}

TEST(WindowBound, NotApplicableWithPeakWindowsOrSections) {
  FleetProblem p = testing::small_fleet(4, 80, 140, 330);
  EnergyModelOptions o;
  o.time_step_s = 0.1;
  o.model = EnergyModel::Sections;
  o.section_boundaries_m = {2000.0};
  const FleetModels sections(testing::small_pattern().trip, p, o);
  EXPECT_FALSE(window_used_regen_bound(sections.profile(), p).applicable);
  std::string why;
  WindowBoundOptions bad;
  bad.short_cell_s = 0;
  EXPECT_FALSE(bad.IsValid(&why));
  EXPECT_NE(why.find("short_cell_s"), std::string::npos);
}

}  // namespace
}  // namespace ecorail::timetable
