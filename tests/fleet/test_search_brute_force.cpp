// The heuristic headway search (regime start, annealing with block moves, anytime rounds,
// polish) against brute force: on fleets of 3-6 trains every timetable of the problem is
// enumerated (departures depth-first, one incremental balance, every train moved once per
// visit), and the search must find the least substation energy among them. Also: more rounds
// are never worse and continue the run with fewer, and the thread count changes nothing.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <stdexcept>
#include <string>

#include "fleet_fixture.hpp"

namespace ecorail::fleet {
namespace {

struct BruteForce {
  MicroJoules best = 0;
  std::vector<int> departures;
  long timetables = 0;
};

BruteForce brute_force(const TestFleet& fleet) {
  const FleetProblem& p = fleet.problem();
  const std::unique_ptr<energy::FleetBalance> balance = fleet.model().make_balance(1);
  std::vector<int> t = departures_from_headways(uniform_headways(p));
  balance->place_all(t);
  BruteForce out;
  bool first = true;
  std::function<void(int)> visit = [&](int k) {
    if (k == p.trains - 1) {
      if (!p.headway_allowed(t[k - 1], t[k])) return;
      ++out.timetables;
      if (first || balance->substation() < out.best) {
        out.best = balance->substation(), out.departures = t, first = false;
      }
      return;
    }
    const int remaining = p.trains - 1 - k;  // headways after train k
    for (int d = t[k - 1] + p.any_headway_min_s(); d <= t[k - 1] + p.any_headway_max_s(); ++d) {
      if (!p.headway_allowed(t[k - 1], d)) continue;
      if (p.span_s - d < remaining * p.any_headway_min_s() ||
          p.span_s - d > remaining * p.any_headway_max_s())
        continue;
      t[k] = d;
      balance->move(k, d);
      visit(k + 1);
    }
  };
  visit(1);
  return out;
}

TestFleet fleet_of(const FleetProblem& p) {
  EnergyModelOptions o;
  o.time_step_s = 1.0;  // the model's grid is the annealing's: brute force sees what it sees
  return TestFleet(testing::small_pattern().trip, p, o);
}

HeadwayOptimiserOptions quick() {
  HeadwayOptimiserOptions o;
  o.moves_per_run = 20000;
  o.threads = 2;
  return o;
}

class SearchVsBruteForce : public ::testing::TestWithParam<int> {};

TEST_P(SearchVsBruteForce, FindsTheOptimum) {
  const int trains = GetParam();
  // Headways around a 100 s mean (4-5 trains on the 480 s trip share regenerated energy), the
  // range narrower for more trains so that brute force stays at a few hundred thousand.
  const int w = trains == 3 ? 40 : trains == 4 ? 30 : trains == 5 ? 20 : 12;
  const TestFleet fleet =
      fleet_of(testing::small_fleet(trains, 100 - w, 100 + w, (trains - 1) * 100));
  const BruteForce brute = brute_force(fleet);
  ASSERT_GT(brute.timetables, 1);
  const HeadwayOptimiserResult r = optimise_headways(fleet, quick());
  const double found = r.evaluation.total.substation_J();
  EXPECT_NEAR(found, to_joules(brute.best), 1e-6) << brute.timetables << " timetables";
  EXPECT_LE(r.evaluation.total.used_regen_J, r.summary.bound_used_regen_J + 1e-6);
}

INSTANTIATE_TEST_SUITE_P(Trains3To6, SearchVsBruteForce, ::testing::Values(3, 4, 5, 6));

// A peak window in the middle of the span: the classes of the search's moves (single and
// block) are those brute force enumerates.
TEST(SearchVsBruteForce, FindsTheOptimumWithAPeakWindow) {
  FleetProblem p = testing::small_fleet(6, 150, 200, 2 * 60 + 3 * 170);
  p.peak_windows = {{200, 320}};
  p.peak_headway_min_s = 50;
  p.peak_headway_max_s = 70;
  const TestFleet fleet = fleet_of(p);
  const BruteForce brute = brute_force(fleet);
  ASSERT_GT(brute.timetables, 1);
  const HeadwayOptimiserResult r = optimise_headways(fleet, quick());
  EXPECT_EQ(departures_problem(p, r.evaluation.departures_s), "");
  EXPECT_NEAR(r.evaluation.total.substation_J(), to_joules(brute.best), 1e-6);
}

// A timetable the caller gives is a start the result never falls below: with no annealing and no
// polish the search alone ends where its own starts are (worse than the brute-force optimum
// here, checked), and with the optimum given it returns the optimum, on the model's grid.
TEST(GivenStart, TheResultIsNeverWorseThanTheGivenTimetable) {
  const TestFleet fleet = fleet_of(testing::small_fleet(6, 88, 112, 5 * 100));
  const BruteForce brute = brute_force(fleet);
  HeadwayOptimiserOptions o = quick();
  o.restarts = 0;
  o.polish_window_s = 0;
  o.exact_refine = false;
  const HeadwayOptimiserResult alone = optimise_headways(fleet, o);
  ASSERT_GT(alone.evaluation.total.substation_J(), to_joules(brute.best) + 1.0);
  EXPECT_TRUE(std::isnan(alone.summary.given_start_used_J));
  o.given_starts_s = {departures_from_headways(uniform_headways(fleet.problem())),
                      brute.departures};
  const HeadwayOptimiserResult given = optimise_headways(fleet, o);
  EXPECT_NEAR(given.evaluation.total.substation_J(), to_joules(brute.best), 1e-6);
  EXPECT_EQ(given.evaluation.departures_s, brute.departures);
  EXPECT_NEAR(given.summary.given_start_used_J, given.evaluation.total.used_regen_J, 1e-6);
  // And with the full search the given optimum stays the result.
  const HeadwayOptimiserResult full = optimise_headways(fleet, [] {
    HeadwayOptimiserOptions q = quick();
    q.moves_per_run = 200;
    return q;
  }());
  o = quick();
  o.moves_per_run = 200;
  o.given_starts_s = {brute.departures};
  EXPECT_LE(optimise_headways(fleet, o).evaluation.total.substation_J(),
            std::min(full.evaluation.total.substation_J(), to_joules(brute.best)) + 1e-6);
}

// A given timetable that breaks the problem is refused, naming what it breaks.
TEST(GivenStart, ATimetableOutsideTheProblemIsRefused) {
  const TestFleet fleet = fleet_of(testing::small_fleet(6, 88, 112, 5 * 100));
  HeadwayOptimiserOptions o = quick();
  o.given_starts_s = {{0, 100, 200, 300, 400, 499}};
  try {
    optimise_headways(fleet, o);
    FAIL() << "a timetable whose last departure misses the span was taken";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("given start"), std::string::npos) << e.what();
  }
}

// Rounds continue the run: with more rounds the result is never worse, and the same for one
// thread and two.
TEST(AnytimeRounds, MoreRoundsNeverWorseAndThreadFree) {
  const TestFleet fleet = fleet_of(testing::small_fleet(14, 60, 140, 13 * 100));
  HeadwayOptimiserOptions o = quick();
  o.moves_per_run = 3000;
  const HeadwayOptimiserResult r0 = optimise_headways(fleet, o);
  o.rounds = 4;
  const HeadwayOptimiserResult r4 = optimise_headways(fleet, o);
  EXPECT_EQ(r4.summary.rounds, 4);
  EXPECT_LE(r4.summary.substation_J, r0.summary.substation_J);
  o.threads = 1;
  const HeadwayOptimiserResult r4_one = optimise_headways(fleet, o);
  EXPECT_EQ(r4_one.evaluation.departures_s, r4.evaluation.departures_s);
}

}  // namespace
}  // namespace ecorail::fleet
