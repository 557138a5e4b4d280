// The Monte Carlo's driven followers (recovery/monte_carlo_followers.hpp) on A6 -> A9 (three
// sections, each planned 15 s above its flat-out run, 30 s dwells): one forced delay that no
// station absorbs (the late train then runs flat out in both programs) against `delay`'s
// follower model (recover_delay, an independent path to the same followers: its own runs, its
// own trips), train by train and stop by stop; every held-up follower keeps its braking distance
// (its least gap >= 0 on the re-simulated runs); random days the same for one and two threads;
// the fast mode says so in its report and in the run's config.
#include <gtest/gtest.h>

#include <cmath>

#include "recovery/delay_recovery.hpp"
#include "recovery/monte_carlo.hpp"
#include "recovery/monte_carlo_run.hpp"
#include "recovery_fixture.hpp"

namespace ecorail::recovery {
namespace {

using testing::small_library;
using testing::small_runs;
using testing::test_store;

// As `delay`: no early running, no take-over (a 90 s delay is recovered, not handed over).
MonteCarloOptions driven_options() {
  MonteCarloOptions o;
  o.knot_step_s = 2.0;
  o.early_s = 0.0;
  o.takeover_s = 3600.0;
  return o;
}

// Three trains 60 s apart, each section 15 s above its flat-out run: the slowest candidate run
// of a held-up follower (10 s above the plan) lies inside the fixture's 30 s frontiers, as it
// does on the reference line's 60 s ones (beyond a frontier's end the Monte Carlo offers its
// last run instead).
const Plan& three_trains() {
  static const Plan plan = [] {
    const dp::SectionLibrary& lib = small_library();
    std::vector<double> times;
    for (std::size_t k = 0; k < lib.size(); ++k)
      times.push_back(std::round((lib.min_time_s(k) + 15.0) * 1000.0) / 1000.0);
    return plan_from_pattern(testing::small_stops(), times, {30.0, 30.0}, {0.0, 60.0, 120.0});
  }();
  return plan;
}

const MonteCarlo& driven() {
  static const MonteCarlo mc(small_library(), three_trains(), driven_options(), small_runs());
  return mc;
}

TEST(MonteCarloFollowers, OneDelayDrivesTheFollowersAsDelayDoes) {
  const Plan& plan = three_trains();
  const std::size_t n = plan.sections();
  for (double delay : {70.0, 110.0}) {
    SCOPED_TRACE("delay " + std::to_string(delay));
    DelayRecoveryOptions o;
    o.max_followers = 5;
    const DelayRecoveryResult ref =
        recover_delay(small_library(), plan, 0, 0, delay, o, test_store());
    ASSERT_FALSE(ref.summary.recovered);  // flat out to the last stop in both programs
    ASSERT_GE(ref.summary.followers_affected, 1);
    const std::vector<ForcedDelay> forced = {{0, 0, delay}};
    std::vector<std::vector<double>> arrivals;
    const DayRecord r = driven().simulate_day(0, &forced, &arrivals);
    EXPECT_EQ(r.followers_held_up, ref.summary.followers_affected);
    // Every train `delay` reports (the late one, then each held-up follower), stop by stop.
    // Tolerance: the Monte Carlo keeps the plan's nominal times where a train runs its plan
    // (the re-simulation meets them within 0.1 s) and checks the separation on samples 1 m
    // apart (5 cm in `delay`).
    for (const AffectedTrain& a : ref.trains) {
      const auto k = static_cast<std::size_t>(a.train);
      for (std::size_t j = 1; j <= n; ++j)
        EXPECT_NEAR(arrivals[k][j] - plan.trains[k].arrival_s[j], a.lateness_s[j], 0.15)
            << "train " << k + 1 << " stop " << j;
    }
    // A follower `delay` finds not held up runs its plan here too.
    for (std::size_t k = ref.trains.size(); k < plan.trains.size(); ++k)
      for (std::size_t j = 1; j <= n; ++j)
        EXPECT_NEAR(arrivals[k][j], plan.trains[k].arrival_s[j], 1e-6);
    // The invariant on the re-simulated runs.
    EXPECT_GE(r.min_follower_gap_m, 0.0);
    EXPECT_GE(r.min_follower_margin_m, -0.01);
    // The held-up followers wait: later than the fast mode's departure gap alone would make them.
    EXPECT_GT(r.knock_on_delays, 0);
  }
}

TEST(MonteCarloFollowers, RandomDaysAreTheSameForAnyThreadCountAndKeepTheBrakingDistance) {
  MonteCarloOptions o = driven_options();
  o.early_s = 10.0;
  ASSERT_TRUE(parse_delay_tail("uniform:30:110", o.delays, nullptr));  // long delays, held up
  o.delays.p_none = 0.4;
  o.delays.p_small = 0.2;
  const MonteCarlo mc(small_library(), three_trains(), o, small_runs());
  const std::vector<DayRecord> one = mc.run_days(0, 12, 1), two = mc.run_days(0, 12, 2);
  ASSERT_EQ(one.size(), two.size());
  std::int64_t held = 0;
  for (std::size_t i = 0; i < one.size(); ++i) {
    EXPECT_EQ(one[i].traction_kJ, two[i].traction_kJ);
    EXPECT_EQ(one[i].lateness_sum_s, two[i].lateness_sum_s);
    EXPECT_EQ(one[i].followers_held_up, two[i].followers_held_up);
    held += one[i].followers_held_up;
    EXPECT_GE(one[i].min_follower_gap_m, 0.0);
  }
  EXPECT_GT(held, 0);  // the check is not empty
}

TEST(MonteCarloFollowers, TheFastModeIsLabelled) {
  MonteCarloOptions o = driven_options();
  o.followers = FollowerModel::Shortcut;
  const MonteCarlo fast(small_library(), three_trains(), o, small_runs());
  MonteCarloRunInfo info;
  info.days_total = 2;
  const MonteCarloDays f = simulate_days(fast, small_runs(), 0, 2, 1, info);
  EXPECT_NE(f.summary.BriefReport().find("fast mode"), std::string::npos);
  EXPECT_EQ(f.run.config.at("followers"), "shortcut");
  EXPECT_EQ(run_summary(f.run).followers, "shortcut");
  const MonteCarloDays d = simulate_days(driven(), small_runs(), 0, 2, 1, info);
  EXPECT_EQ(d.summary.BriefReport().find("fast mode"), std::string::npos);
  EXPECT_NE(d.summary.BriefReport().find("followers driven"), std::string::npos);
  EXPECT_EQ(d.run.config.at("followers"), "driven");
  EXPECT_EQ(follower_model_from_name("shortcut"), FollowerModel::Shortcut);
  EXPECT_FALSE(follower_model_from_name("fast").has_value());
}

}  // namespace
}  // namespace ecorail::recovery
