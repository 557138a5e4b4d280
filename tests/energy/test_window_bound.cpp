// The window bound (energy/window_bound.hpp) on fleets small enough to enumerate every
// timetable (3 to 6 trains of the small pattern, trip 480 s, so the core starts at 120 s): the
// relaxed value of every timetable is at least its used energy (each window term bounds its
// share), equal to it on the bound's grid when every headway lies in the core (the
// decomposition is exact there), and the bound is never below the brute-force optimum, on the
// model's grid and on a coarser one. The power-flow model certifies with it, and the headway
// optimiser's gap then covers its true shortfall.
#include <gtest/gtest.h>

#include <algorithm>
#include <functional>
#include <random>

#include "../fleet/fleet_fixture.hpp"
#include "energy/window_bound.hpp"

namespace ecorail::fleet {
namespace {

using energy::window_relaxed_values_J;
using energy::window_used_regen_bound;
using energy::WindowBound;
using energy::WindowBoundOptions;

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

// The most any timetable of the problem uses, by enumeration.
double brute_force_best_used_J(const TestFleet& fleet, const FleetProblem& p) {
  auto balance = fleet.make_balance();
  double best = 0.0;
  for_each_timetable(p, [&](const std::vector<int>& h) {
    balance->place_all(departures_from_headways(h));
    best = std::max(best, to_joules(balance->used()));
  });
  return best;
}

struct Case {
  int trains, hmin, hmax, span;
};

// Headways 80-140 cover the core (from 120 s) and cells below it; the spans are chosen so that
// some timetables are all-core and some are not.
TEST(WindowBound, EveryTimetableBelowItsRelaxedValueAndTheBoundAboveTheOptimum) {
  for (const Case c : {Case{3, 80, 200, 280}, Case{4, 80, 140, 380}, Case{5, 90, 140, 500},
                       Case{6, 110, 130, 620}}) {
    const FleetProblem p = testing::small_fleet(c.trains, c.hmin, c.hmax, c.span);
    const TestFleet fleet(testing::small_pattern().trip, p, testing::tenth_of_a_second());
    WindowBoundOptions wo;
    wo.short_cell_s = 7;
    wo.bound_ticks_per_second = 10;  // the model's grid: exact on the core
    const WindowBound bound = window_used_regen_bound(fleet.profile(), limits_of(p), wo);
    ASSERT_TRUE(bound.applicable) << bound.why_not;
    auto balance = fleet.make_balance();
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
    const std::vector<double> relaxed =
        window_relaxed_values_J(fleet.profile(), limits_of(p), sample, wo);
    for (std::size_t i = 0; i < sample.size(); ++i) {
      const double used = used_of_sample[i];
      EXPECT_GE(relaxed[i], used * (1 - 1e-12)) << c.trains << " trains, timetable " << i;
      if (*std::min_element(sample[i].begin(), sample[i].end()) >= bound.core_min_s) {
        ++core;
        // Exact up to the tables' rounding up to floats (a few parts in 1e8 of each term).
        EXPECT_NEAR(relaxed[i], used, 1e-6 * used + 1e-3) << "core timetable: exact decomposition";
      }
    }
    EXPECT_GT(timetables, 10);
    EXPECT_GT(core, 0) << c.trains << " trains: no all-core timetable sampled";
    EXPECT_GT(best, 0.0);
    EXPECT_GE(bound.bound_used_J, best * (1 - 1e-12)) << c.trains << " trains";
    // A coarser grid of the bound (1 s bins, each a union of ten of the model's) only loosens.
    wo.bound_ticks_per_second = 1;
    const WindowBound coarse = window_used_regen_bound(fleet.profile(), limits_of(p), wo);
    EXPECT_GE(coarse.bound_used_J, best * (1 - 1e-12)) << c.trains << " trains, 1 s grid";
    const std::vector<double> relaxed_coarse =
        window_relaxed_values_J(fleet.profile(), limits_of(p), sample, wo);
    for (std::size_t i = 0; i < sample.size(); ++i)
      EXPECT_GE(relaxed_coarse[i], used_of_sample[i] * (1 - 1e-12)) << "1 s grid, " << i;
  }
}

// Many trains on the line: headways far below the core (down to a twelfth of the trip), so that
// five, six and more trains share the line and the fifth train's charges of every band of
// short_band_ends_s are what covers their share. Random timetables of nine trains (a fixed
// seed): the relaxed value of each is at least its used energy, and the bound at least the best.
// Cells of 1 s keep the triples below the core tight, so the charges must do the work: with them
// set to zero, 12 of the 400 timetables fell below their used energy (checked once by hand).
TEST(WindowBound, ChargesCoverFiveAndMoreTrainsOnTheLine) {
  const FleetProblem p = testing::small_fleet(9, 40, 140, 8 * 100);
  const TestFleet fleet(testing::small_pattern().trip, p, testing::tenth_of_a_second());
  WindowBoundOptions wo;
  wo.short_cell_s = 1;
  wo.short_band_ends_s = {10, 30, 60};
  const WindowBound bound = window_used_regen_bound(fleet.profile(), limits_of(p), wo);
  ASSERT_TRUE(bound.applicable) << bound.why_not;
  const int L = static_cast<int>(bound.active_s);
  std::mt19937 rng(23);
  std::uniform_int_distribution<int> pick(p.headway_min_s, p.headway_max_s);
  std::vector<std::vector<int>> sample;
  std::vector<double> used;
  auto balance = fleet.make_balance();
  int five = 0, six = 0;
  while (sample.size() < 400) {
    std::vector<int> h(p.trains - 1);
    int sum = 0;
    for (std::size_t i = 0; i + 1 < h.size(); ++i) sum += h[i] = pick(rng);
    h.back() = p.span_s - sum;
    if (h.back() < p.headway_min_s || h.back() > p.headway_max_s) continue;
    int most = 1;  // most trains on the line at once (m consecutive headways below L)
    for (std::size_t i = 0; i < h.size(); ++i) {
      int s = 0;
      for (std::size_t m = i; m < h.size() && (s += h[m]) < L; ++m)
        most = std::max(most, static_cast<int>(m - i) + 2);
    }
    five += most >= 5;
    six += most >= 6;
    balance->place_all(departures_from_headways(h));
    used.push_back(to_joules(balance->used()));
    sample.push_back(h);
  }
  EXPECT_GT(five, 100);
  EXPECT_GT(six, 10);
  const std::vector<double> relaxed =
      window_relaxed_values_J(fleet.profile(), limits_of(p), sample, wo);
  for (std::size_t i = 0; i < sample.size(); ++i)
    EXPECT_GE(relaxed[i], used[i] * (1 - 1e-12)) << "timetable " << i;
  EXPECT_GE(bound.bound_used_J, *std::max_element(used.begin(), used.end()) * (1 - 1e-12));
}

// The multiplier search ends within its tolerance of the dual's minimum (the crossing of the
// tangents of its bracket), no multiplier tried gives a lower bound than that minimum, and the
// bound does not depend on the thread count.
TEST(WindowBound, TheMultiplierSearchEndsAtTheDualsMinimum) {
  const FleetProblem p = testing::small_fleet(8, 90, 160, 7 * 128);
  const TestFleet fleet(testing::small_pattern().trip, p, testing::tenth_of_a_second());
  WindowBoundOptions wo;
  wo.max_dual_evaluations = 60;
  const WindowBound bound = window_used_regen_bound(fleet.profile(), limits_of(p), wo);
  ASSERT_TRUE(bound.applicable) << bound.why_not;
  EXPECT_LT(bound.evaluations, wo.max_dual_evaluations);
  EXPECT_LE(bound.dual_floor_J, bound.bound_used_J);
  EXPECT_LE(bound.bound_used_J - bound.dual_floor_J,
            wo.multiplier_tolerance * bound.bound_used_J + 1e-9 * bound.bound_used_J + 1e-3);
  // The same bound, bit for bit, on one thread and on two.
  WindowBoundOptions one_thread = wo, two_threads = wo;
  one_thread.threads = 1;
  two_threads.threads = 2;
  EXPECT_EQ(window_used_regen_bound(fleet.profile(), limits_of(p), one_thread).bound_used_J,
            window_used_regen_bound(fleet.profile(), limits_of(p), two_threads).bound_used_J);
  // Any other multiplier: a valid bound too, never a lower one.
  for (int i = 1; i <= 3; ++i) {
    WindowBoundOptions one = wo;
    one.max_dual_evaluations = i;
    EXPECT_GE(window_used_regen_bound(fleet.profile(), limits_of(p), one).bound_used_J,
              bound.dual_floor_J);
  }
}

// A stop (a time limit) may end the bound anywhere: while its tables are built (then it does not
// apply) or between its DP layers (then it keeps the best multiplier of the runs that finished).
// Whatever it keeps is still at least the brute-force optimum and never below the full bound.
TEST(WindowBound, AStopAnywhereKeepsAValidBound) {
  const FleetProblem p = testing::small_fleet(5, 90, 140, 500);
  const TestFleet fleet(testing::small_pattern().trip, p, testing::tenth_of_a_second());
  const double best = brute_force_best_used_J(fleet, p);
  WindowBoundOptions wo;
  wo.threads = 1;  // the stop's calls then come in one order
  long calls = 0;
  wo.stop = [&calls] {
    ++calls;
    return false;
  };
  const WindowBound full = window_used_regen_bound(fleet.profile(), limits_of(p), wo);
  ASSERT_TRUE(full.applicable) << full.why_not;
  EXPECT_FALSE(full.stopped);
  ASSERT_GE(full.evaluations, 2);
  const long total = calls;
  int before_tables = 0, between_runs = 0;
  for (long at = 1; at <= total + 1; ++at) {
    long n = 0;
    WindowBoundOptions cut = wo;
    cut.stop = [&n, at] { return ++n >= at; };
    const WindowBound b = window_used_regen_bound(fleet.profile(), limits_of(p), cut);
    if (at > total) {  // never asked that often: the full bound, bit for bit
      EXPECT_FALSE(b.stopped);
      EXPECT_EQ(b.bound_used_J, full.bound_used_J);
      continue;
    }
    ASSERT_TRUE(b.stopped) << at;
    if (!b.applicable) {
      ++before_tables;
      EXPECT_EQ(b.evaluations, 0);
      continue;
    }
    ++between_runs;
    EXPECT_GE(b.evaluations, 1);
    EXPECT_LT(b.evaluations, full.evaluations + 1);
    EXPECT_GE(b.bound_used_J, best * (1 - 1e-12)) << at;
    EXPECT_GE(b.bound_used_J, full.bound_used_J) << at;
    EXPECT_NE(energy::window_cut_short(b).find("after"), std::string::npos);
  }
  EXPECT_GT(before_tables, 0);
  EXPECT_GT(between_runs, 0);
  // The model's certificate says when the limit cut its bound, and stays a bound.
  const energy::FleetLowerBound lb = fleet.model().lower_bound([] { return true; });
  EXPECT_NE(lb.name.find("cut short by the time limit"), std::string::npos) << lb.name;
  EXPECT_GE(lb.used_regen_J, best * (1 - 1e-12));
}

// The power-flow model certifies with the window bound, and the optimiser's gap covers its true
// shortfall from the brute-force optimum.
TEST(WindowBound, ThePowerFlowModelsCertificateCoversTheTrueShortfall) {
  const FleetProblem p = testing::small_fleet(5, 90, 140, 500);
  const TestFleet fleet(testing::small_pattern().trip, p, testing::tenth_of_a_second());
  const double best = brute_force_best_used_J(fleet, p);
  const energy::FleetLowerBound lb = fleet.model().lower_bound();
  EXPECT_EQ(lb.name, "window bound");
  EXPECT_GE(lb.used_regen_J, best * (1 - 1e-12));
  HeadwayOptimiserOptions opt;
  opt.moves_per_run = 2000;
  opt.polish_window_s = 60;
  const HeadwayOptimiserResult r = optimise_headways(fleet, opt);
  EXPECT_LE(r.summary.used_regen_J, best * (1 + 1e-12));
  EXPECT_GE(r.summary.bound_used_regen_J, best * (1 - 1e-12));
  EXPECT_GE(r.summary.gap_fraction * r.summary.substation_J,
            (best - r.summary.used_regen_J) * (1 - 1e-9));
  EXPECT_NE(r.summary.method.find("window bound"), std::string::npos) << r.summary.method;
}

// The maximisers in the core (the search's starts, window_core_maximisers): every headway lies
// in the core, and each is the best all-core sequence of its own sum (a maximiser at any
// multiplier beats every sequence of the same sum), checked against every such sequence. The
// power-flow model offers them; a model without the capability offers none.
TEST(WindowBound, CoreMaximisersAreTheBestSequencesOfTheirSum) {
  const FleetProblem p = testing::small_fleet(5, 90, 150, 540);
  const TestFleet fleet(testing::small_pattern().trip, p, testing::tenth_of_a_second());
  const WindowBound bound = window_used_regen_bound(fleet.profile(), limits_of(p));
  ASSERT_TRUE(bound.applicable) << bound.why_not;
  const int hc = bound.core_min_s, hmax = p.headway_max_s;
  ASSERT_GT(hc, p.headway_min_s);
  const std::vector<std::vector<int>> maximisers =
      energy::window_core_maximisers(fleet.profile(), limits_of(p));
  ASSERT_GE(maximisers.size(), 2u);
  EXPECT_EQ(fleet.model().relaxation_maximisers_s(), maximisers);
  energy::FleetLimits core = limits_of(p);
  core.headway_min_s = hc;
  bool above = false, below = false;
  for (const std::vector<int>& m : maximisers) {
    ASSERT_EQ(m.size(), 4u);
    int sum = 0;
    for (const int h : m) {
      EXPECT_GE(h, hc);
      EXPECT_LE(h, hmax);
      sum += h;
    }
    above |= sum >= p.span_s, below |= sum <= p.span_s;
    std::vector<std::vector<int>> same_sum;
    for (int a = hc; a <= hmax; ++a)
      for (int b = hc; b <= hmax; ++b)
        for (int c = hc; c <= hmax; ++c)
          if (const int d = sum - a - b - c; d >= hc && d <= hmax) same_sum.push_back({a, b, c, d});
    const double own = window_relaxed_values_J(fleet.profile(), core, {m}).front();
    const std::vector<double> others = window_relaxed_values_J(fleet.profile(), core, same_sum);
    const double best = *std::max_element(others.begin(), others.end());
    EXPECT_GE(own, best - 1e-7 * best - 1e-3) << "maximiser of sum " << sum;
  }
  EXPECT_TRUE(above && below) << "the maximisers' sums bracket the span";
  EnergyModelOptions overlap = testing::tenth_of_a_second();
  overlap.model = "overlap";
  EXPECT_TRUE(TestFleet(testing::small_pattern().trip, p, overlap)
                  .model()
                  .relaxation_maximisers_s()
                  .empty());
}

TEST(WindowBound, NotApplicableWithSectionsOrPeakClasses) {
  const FleetProblem p = testing::small_fleet(4, 80, 140, 330);
  EnergyModelOptions o = testing::tenth_of_a_second();
  o.model = "sections";
  o.section_boundaries_m = {2000.0};
  const TestFleet sections(testing::small_pattern().trip, p, o);
  EXPECT_FALSE(window_used_regen_bound(sections.profile(), limits_of(p)).applicable);
  EXPECT_EQ(sections.model().lower_bound().name, "pair bound");
  FleetProblem peak = p;
  peak.peak_windows = {{0, 100}};
  EXPECT_EQ(limits_of(peak).headway_classes, 2);
  const TestFleet power_flow(testing::small_pattern().trip, p, testing::tenth_of_a_second());
  EXPECT_FALSE(window_used_regen_bound(power_flow.profile(), limits_of(peak)).applicable);
  std::string why;
  WindowBoundOptions bad;
  bad.short_cell_s = 0;
  EXPECT_FALSE(bad.IsValid(&why));
  EXPECT_NE(why.find("short_cell_s"), std::string::npos);
}

}  // namespace
}  // namespace ecorail::fleet
