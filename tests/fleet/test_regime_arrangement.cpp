// The reordering of a regime start's runs within their stretches (fleet/regime_arrangement.hpp),
// against the model's own evaluation: it never loses used energy, keeps every stretch's span and
// headways (so the problem's windows), gains at least the best single move found by an
// independent enumeration, and with two runs in a stretch finds the better of their two orders.
#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>

#include "fleet/regime_arrangement.hpp"
#include "fleet/windowed_classes.hpp"
#include "fleet_fixture.hpp"

namespace ecorail::fleet {
namespace {

// Off-peak 80-200 s, a peak window (800, 1100) s at 60-70 s: two off-peak stretches around a
// peak stretch of six headways.
FleetProblem windowed_problem(int span_s) {
  FleetProblem p = testing::small_fleet(20, 80, 200, span_s);
  p.peak_windows = {{800, 1100}};
  p.peak_headway_min_s = 60;
  p.peak_headway_max_s = 70;
  return p;
}

struct Start {
  std::vector<int> headways_s, labels;
  void add(std::vector<int> h, int label) {
    for (int x : h) headways_s.push_back(x), labels.push_back(label);
  }
};

// 90 x3 (B), 85/105 x2 (A, alternating), 150 (C) to 800 s | 60 x5 (P) to 1100 s |
// 130 x2 (D), 85 x4 (E).
Start three_stretches() {
  Start s;
  s.add({90, 90, 90}, 1);
  s.add({85, 105, 85, 105}, 2);
  s.add({150}, 3);
  s.add({60, 60, 60, 60, 60}, 4);
  s.add({130, 130}, 5);
  s.add({85, 85, 85, 85}, 6);
  return s;
}

double used_of(const TestFleet& fleet, const std::vector<int>& h) {
  return fleet.evaluate(departures_from_headways(h)).total.used_regen_J;
}

// The problem whose span is the start's, checked to hold the start.
FleetProblem problem_for(const Start& s) {
  const FleetProblem p =
      windowed_problem(std::accumulate(s.headways_s.begin(), s.headways_s.end(), 0));
  EXPECT_EQ(departures_problem(p, departures_from_headways(s.headways_s)), "");
  return p;
}

EnergyModelOptions one_second() {
  EnergyModelOptions o;
  o.time_step_s = 1.0;
  return o;
}

TEST(RegimeArrangement, NeverLosesAndKeepsEveryStretch) {
  const Start s = three_stretches();
  const FleetProblem p = problem_for(s);
  const TestFleet fleet(testing::small_pattern().trip, p, one_second());
  const RegimeArrangement a = arrange_regime_runs(fleet.model(), p, s.headways_s, s.labels);
  EXPECT_NEAR(a.start_used_J, used_of(fleet, s.headways_s), 1e-6);
  EXPECT_GE(a.used_J, a.start_used_J);
  EXPECT_NEAR(a.used_J, used_of(fleet, a.headways_s), 1e-6);  // its figure is its timetable's
  EXPECT_EQ(departures_problem(p, departures_from_headways(a.headways_s)), "");
  // Each stretch (index ranges 0-7, 8-12, 13-18) keeps its headways in some order.
  for (auto [b, e] : {std::pair{0, 8}, {8, 13}, {13, 19}}) {
    std::vector<int> x(s.headways_s.begin() + b, s.headways_s.begin() + e);
    std::vector<int> y(a.headways_s.begin() + b, a.headways_s.begin() + e);
    std::sort(x.begin(), x.end());
    std::sort(y.begin(), y.end());
    EXPECT_EQ(x, y) << "stretch from headway " << b;
  }
  ASSERT_EQ(a.run_of_headway.size(), a.headways_s.size());
  // A start that breaks the problem's rules is refused, not rearranged.
  std::vector<int> broken = s.headways_s;
  broken[0] = 70;
  broken[1] = 110;
  EXPECT_THROW(arrange_regime_runs(fleet.model(), p, broken, s.labels), std::invalid_argument);
}

// Every single move of the start, enumerated here on its own: relocations of one run to another
// place in its stretch, and the phase swap of the alternating run. The first round keeps at least
// the best of them.
TEST(RegimeArrangement, GainsAtLeastTheBestSingleMove) {
  const Start s = three_stretches();
  const FleetProblem p = problem_for(s);
  const TestFleet fleet(testing::small_pattern().trip, p, one_second());
  using Runs = std::vector<std::vector<int>>;
  const Runs first = {{90, 90, 90}, {85, 105, 85, 105}, {150}};
  const Runs last = {{130, 130}, {85, 85, 85, 85}};
  const std::vector<int> peak(5, 60);
  const auto join = [&](const Runs& a, const Runs& b) {
    std::vector<int> h;
    for (const auto& r : a) h.insert(h.end(), r.begin(), r.end());
    h.insert(h.end(), peak.begin(), peak.end());
    for (const auto& r : b) h.insert(h.end(), r.begin(), r.end());
    return h;
  };
  double best = used_of(fleet, s.headways_s);
  int priced = 0;
  const auto relocations = [&](const Runs& runs, auto&& make) {
    for (std::size_t i = 0; i < runs.size(); ++i)
      for (std::size_t j = 0; j < runs.size(); ++j) {
        if (j == i) continue;
        Runs r = runs;
        const std::vector<int> moved = r[i];
        r.erase(r.begin() + i);
        r.insert(r.begin() + j, moved);
        best = std::max(best, used_of(fleet, make(r))), ++priced;
      }
  };
  relocations(first, [&](const Runs& r) { return join(r, last); });
  relocations(last, [&](const Runs& r) { return join(first, r); });
  best = std::max(best, used_of(fleet, join({{90, 90, 90}, {105, 85, 105, 85}, {150}}, last)));
  EXPECT_EQ(priced, 6 + 2);
  RegimeArrangementOptions o;
  o.max_rounds = 1;
  const RegimeArrangement a = arrange_regime_runs(fleet.model(), p, s.headways_s, s.labels, o);
  EXPECT_GE(a.used_J, best - 1e-6);
  EXPECT_GT(best, a.start_used_J);  // the case is not trivial: some move gains
}

// A stretch of two runs has two orders: the arrangement ends at the better one.
TEST(RegimeArrangement, TwoRunsEndInTheBetterOrder) {
  Start s;
  s.add({95, 95, 95, 95}, 1);
  s.add({200, 200}, 2);
  s.add({60, 60, 60, 60, 60, 60}, 3);
  s.add({120, 120, 120, 120, 120, 120, 120}, 4);
  const FleetProblem p = problem_for(s);
  const TestFleet fleet(testing::small_pattern().trip, p, one_second());
  std::vector<int> swapped = s.headways_s;
  std::rotate(swapped.begin(), swapped.begin() + 4, swapped.begin() + 6);
  const double best = std::max(used_of(fleet, s.headways_s), used_of(fleet, swapped));
  const RegimeArrangement a = arrange_regime_runs(fleet.model(), p, s.headways_s, s.labels);
  EXPECT_NEAR(a.used_J, best, 1e-6);
}

// Out of time before its first round, the reordering returns the start as it was.
TEST(RegimeArrangement, StoppedBeforeItsFirstRoundKeepsTheStart) {
  const Start s = three_stretches();
  const FleetProblem p = problem_for(s);
  const TestFleet fleet(testing::small_pattern().trip, p, one_second());
  RegimeArrangementOptions o;
  o.stop = [] { return true; };
  const RegimeArrangement a = arrange_regime_runs(fleet.model(), p, s.headways_s, s.labels, o);
  EXPECT_EQ(a.headways_s, s.headways_s);
  EXPECT_EQ(a.rounds, 0);
  EXPECT_EQ(a.used_J, a.start_used_J);
}

}  // namespace
}  // namespace ecorail::fleet
