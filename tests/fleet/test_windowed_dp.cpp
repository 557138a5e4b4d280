// Headway classes by the clock (question 2.2): the exact windowed DPs against brute force on
// instances small enough to enumerate every timetable, the feasibility check (a case with too
// few trains for the windows is an error naming each window's need), and the uniform-within-
// class timetable.
#include <gtest/gtest.h>

#include <functional>
#include <random>

#include "fleet/fleet_problem.hpp"
#include "fleet/windowed_classes.hpp"
#include "fleet/windowed_dp.hpp"

namespace ecorail::fleet {
namespace {

// A small day: span 80 s, one peak window (30, 45), peak headways 3-5 s, off-peak 8-12 s.
// Question 2.2's day: 240 trains over 63 900 s, peak windows (7200, 12600) and (43200, 50400),
// peak headways 120-150 s, others 300-660 s.
FleetProblem reference_day() {
  FleetProblem p;
  p.trains = 240;
  p.headway_min_s = 300;
  p.headway_max_s = 660;
  p.peak_windows = {{7200, 12600}, {43200, 50400}};
  return p;
}

FleetProblem small_day(int trains) {
  FleetProblem p;
  p.trains = trains;
  p.span_s = 80;
  p.headway_min_s = 8;
  p.headway_max_s = 12;
  p.peak_headway_min_s = 3;
  p.peak_headway_max_s = 5;
  p.peak_windows = {{30, 45}};
  return p;
}

// Every timetable of the problem (departures), checked by headway_allowed alone.
void for_each_windowed(const FleetProblem& p,
                       const std::function<void(const std::vector<int>&)>& f) {
  std::vector<int> t{0};
  std::function<void()> rec = [&]() {
    if (static_cast<int>(t.size()) == p.trains) {
      if (t.back() == p.span_s) f(t);
      return;
    }
    for (int h = p.any_headway_min_s(); h <= p.any_headway_max_s(); ++h) {
      if (t.back() + h > p.span_s || !p.headway_allowed(t.back(), t.back() + h)) continue;
      t.push_back(t.back() + h);
      rec();
      t.pop_back();
    }
  };
  rec();
}

WindowedValue random_values(const FleetProblem& p, std::mt19937_64& rng) {
  WindowedValue v;
  std::uniform_real_distribution<double> u(-5, 5);
  for (int h = p.any_headway_min_s(); h <= p.any_headway_max_s(); ++h) {
    v.peak.push_back(u(rng));
    v.offpeak.push_back(u(rng));
  }
  return v;
}

double value_of(const FleetProblem& p, const WindowedValue& v, const std::vector<int>& t) {
  double x = 0.0;
  for (std::size_t k = 1; k < t.size(); ++k) {
    const int e = t[k] - t[k - 1] - p.any_headway_min_s();
    x += is_peak_headway(p.peak_windows, t[k - 1], t[k]) ? v.peak[e] : v.offpeak[e];
  }
  return x;
}

TEST(WindowedDp, SeparableEqualsBruteForce) {
  std::mt19937_64 rng(3);
  int checked = 0;
  for (int trains = 8; trains <= 14; ++trains) {
    const FleetProblem p = small_day(trains);
    const bool feasible = WindowedReach(p).feasible();
    int count = 0;
    for (int trial = 0; trial < 5; ++trial) {
      const WindowedValue v = random_values(p, rng);
      double best = -1e300;
      count = 0;
      for_each_windowed(p, [&](const std::vector<int>& t) {
        best = std::max(best, value_of(p, v, t));
        ++count;
      });
      ASSERT_EQ(feasible, count > 0) << trains << " trains";
      if (!feasible) {
        EXPECT_THROW(maximise_windowed(p, v), std::invalid_argument);
        continue;
      }
      const HeadwayChoice c = maximise_windowed(p, v);
      const std::vector<int> t = departures_from_headways(c.headways_s);
      EXPECT_EQ(departures_problem(p, t), "");
      EXPECT_NEAR(c.value, best, 1e-9);
      EXPECT_NEAR(value_of(p, v, t), best, 1e-9);
      ++checked;
    }
  }
  EXPECT_GE(checked, 10);  // the sweep over train counts holds feasible instances
}

TEST(WindowedDp, ChainEqualsBruteForce) {
  std::mt19937_64 rng(5);
  for (int trains : {9, 10, 11}) {
    const FleetProblem p = small_day(trains);
    if (!WindowedReach(p).feasible()) continue;
    const int lo = p.any_headway_min_s(), m = p.any_headway_max_s() - lo + 1;
    for (int trial = 0; trial < 3; ++trial) {
      const WindowedValue v = random_values(p, rng);
      std::vector<double> penalty(m * m);
      for (double& x : penalty)
        x = rng() % 3 == 0 ? std::uniform_real_distribution<>(0, 4)(rng) : 0;
      auto chain = [&](const std::vector<int>& t) {
        double x = value_of(p, v, t);
        for (std::size_t k = 2; k < t.size(); ++k)
          x -= penalty[(t[k - 1] - t[k - 2] - lo) * m + (t[k] - t[k - 1] - lo)];
        return x;
      };
      double best = -1e300;
      for_each_windowed(p, [&](const std::vector<int>& t) { best = std::max(best, chain(t)); });
      const HeadwayChoice c = maximise_windowed_chain(p, v, penalty);
      const std::vector<int> t = departures_from_headways(c.headways_s);
      EXPECT_EQ(departures_problem(p, t), "");
      EXPECT_NEAR(c.value, best, 1e-9);
      EXPECT_NEAR(chain(t), best, 1e-9);
    }
  }
}

// Beyond brute force: with no penalty the chain DP must find the separable DP's optimum (a
// second algorithm) on a day with two windows and wide ranges, where its layered layout
// (states reachable from both ends, ranges of last headways) is exercised.
TEST(WindowedDp, ChainWithoutPenaltyEqualsSeparableOnALargerDay) {
  FleetProblem p;
  p.trains = 60;
  p.span_s = 6000;
  p.headway_min_s = 100;
  p.headway_max_s = 160;
  p.peak_headway_min_s = 40;
  p.peak_headway_max_s = 60;
  p.peak_windows = {{1000, 1800}, {4000, 4600}};
  ASSERT_TRUE(WindowedReach(p).feasible());
  std::mt19937_64 rng(11);
  const int m = p.any_headway_max_s() - p.any_headway_min_s() + 1;
  for (int trial = 0; trial < 3; ++trial) {
    const WindowedValue v = random_values(p, rng);
    const HeadwayChoice sep = maximise_windowed(p, v);
    const HeadwayChoice chain =
        maximise_windowed_chain(p, v, std::vector<double>(static_cast<std::size_t>(m) * m, 0.0));
    const std::vector<int> t = departures_from_headways(chain.headways_s);
    EXPECT_EQ(departures_problem(p, t), "");
    EXPECT_NEAR(chain.value, sep.value, 1e-9);
    EXPECT_NEAR(value_of(p, v, t), sep.value, 1e-9);
  }
}

TEST(WindowedDp, TooFewTrainsForTheWindowsIsAnError) {
  // The reference day: 240 trains fit; 100 cannot fill the peak windows at 150 s at most.
  FleetProblem p = reference_day();
  std::string why;
  EXPECT_TRUE(p.IsValid(&why)) << why;
  p.trains = 100;
  EXPECT_FALSE(p.IsValid(&why));
  EXPECT_NE(why.find("peak window 1 (7200-12600 s) needs at least 36 peak headways"),
            std::string::npos)
      << why;
  EXPECT_NE(why.find("peak window 2 (43200-50400 s) needs at least 48 peak headways"),
            std::string::npos)
      << why;
  // The count range it states is exact on the small day (brute force over train counts).
  const FleetProblem small = small_day(2);
  const auto [fewest, most] = windowed_headway_count_range(small);
  int lo = 1000, hi = -1;
  for (int trains = 2; trains <= 30; ++trains) {
    bool any = false;
    for_each_windowed(small_day(trains), [&](const std::vector<int>&) { any = true; });
    if (any) lo = std::min(lo, trains - 1), hi = std::max(hi, trains - 1);
    EXPECT_EQ(any, WindowedReach(small_day(trains)).feasible()) << trains;
  }
  EXPECT_EQ(fewest, lo);
  EXPECT_EQ(most, hi);
}

TEST(WindowedDp, DeparturesBreakingAClassAreNamed) {
  FleetProblem p = small_day(11);
  std::vector<int> t;
  for_each_windowed(p, [&](const std::vector<int>& x) {
    if (t.empty()) t = x;
  });
  ASSERT_FALSE(t.empty());
  EXPECT_EQ(departures_problem(p, t), "");
  // Widen the peak: the same departures now hold an off-peak-sized headway in a peak window.
  p.peak_windows = {{0, 80}};
  EXPECT_NE(departures_problem(p, t).find("a peak headway"), std::string::npos);
}

TEST(WindowedDp, UniformIsEvenWithinEveryRunOfOneClass) {
  FleetProblem p = reference_day();
  const std::vector<int> t = departures_from_headways(uniform_headways(p));
  ASSERT_EQ(departures_problem(p, t), "");
  // The least sum of squares: within a run of consecutive headways of one class, moving a
  // second from one to another keeps every class, so no two differ by more than a second.
  int runs = 0;
  for (std::size_t k = 1; k < t.size();) {
    const bool peak = is_peak_headway(p.peak_windows, t[k - 1], t[k]);
    int lo = 1 << 30, hi = 0;
    std::size_t j = k;
    for (; j < t.size() && is_peak_headway(p.peak_windows, t[j - 1], t[j]) == peak; ++j)
      lo = std::min(lo, t[j] - t[j - 1]), hi = std::max(hi, t[j] - t[j - 1]);
    EXPECT_LE(hi - lo, 1) << "run from " << t[k - 1] << " s";
    k = j;
    ++runs;
  }
  EXPECT_EQ(runs, 5);  // off-peak, peak, off-peak, peak, off-peak
}

TEST(WindowedDp, NearestToClassTargetsKeepsTheClasses) {
  FleetProblem p = reference_day();
  const std::vector<int> h = windowed_nearest_headways(p, 149.0, 331.5);
  const std::vector<int> t = departures_from_headways(h);
  ASSERT_EQ(departures_problem(p, t), "");
  // No single headway can be nearer its target by a move that keeps the others: a brute check
  // of the objective against the uniform timetable, which is feasible too.
  auto distance = [&](const std::vector<int>& x) {
    double d = 0.0;
    for (std::size_t k = 1; k < x.size(); ++k) {
      const double target = is_peak_headway(p.peak_windows, x[k - 1], x[k]) ? 149.0 : 331.5;
      d += (x[k] - x[k - 1] - target) * (x[k] - x[k - 1] - target);
    }
    return d;
  };
  EXPECT_LE(distance(t), distance(departures_from_headways(uniform_headways(p))));
}

}  // namespace
}  // namespace ecorail::fleet
