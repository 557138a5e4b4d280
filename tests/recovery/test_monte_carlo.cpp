// Monte Carlo service days (question 3.2) on A6 -> A9 (three sections, each planned 20 s above
// its flat-out run, 30 s dwells): the delay distribution against its probabilities (binomial
// tolerance) and its keying; a day without delays against an independent evaluation of the
// plan (re-solved runs, whole trips in the fleet's power balance); one forced delay against
// question 3.1's recovery (a second path to the same times and energy); exact recovery never
// costs more traction than the rule on the same days; statistics byte for byte the same for
// one thread, two threads and two shards merged; the confidence interval against a closed form.
#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "energy/power_flow_balance.hpp"
#include "energy/power_flow_profile.hpp"
#include "fleet/fleet_pattern.hpp"
#include "output/section_run_cache.hpp"
#include "recovery/delay_recovery.hpp"
#include "recovery/monte_carlo.hpp"
#include "recovery_fixture.hpp"

namespace ecorail::recovery {
namespace {

using testing::small_library;
using testing::small_plan;
using testing::small_runs;
using testing::test_store;

MonteCarloOptions small_options() {
  MonteCarloOptions o;
  o.knot_step_s = 2.0;
  return o;
}

TEST(DelayModel, DrawsMatchTheProbabilitiesWithinBinomialTolerance) {
  const DelayDistribution d;
  const int n = 200000;
  int none = 0, small = 0, tail = 0;
  double excess_sum = 0.0;
  for (int i = 0; i < n; ++i) {
    const DelayDraw x =
        draw_delay(d, 7, static_cast<std::uint64_t>(i / 1000),
                   static_cast<std::uint64_t>((i / 13) % 77), static_cast<std::uint64_t>(i % 13));
    if (x.kind == DelayKind::None) {
      ++none;
      EXPECT_EQ(x.delay_s, 0.0);
    } else if (x.kind == DelayKind::Small) {
      ++small;
      EXPECT_GT(x.delay_s, 0.0);
      EXPECT_LE(x.delay_s, 10.0);
    } else {
      ++tail;
      EXPECT_GT(x.delay_s, 10.0);
      excess_sum += x.delay_s - 10.0;
    }
  }
  // Five binomial standard deviations: a correct generator fails this about once in 10^6 runs.
  auto check = [&](int count, double p) {
    const double sd = std::sqrt(p * (1.0 - p) / n);
    EXPECT_NEAR(static_cast<double>(count) / n, p, 5.0 * sd) << "p = " << p;
  };
  check(none, 0.7);
  check(small, 0.2);
  check(tail, 0.1);
  // The exponential tail's excess has mean 30 s and standard deviation 30 s.
  EXPECT_NEAR(excess_sum / tail, 30.0, 5.0 * 30.0 / std::sqrt(static_cast<double>(tail)));
}

TEST(DelayModel, ADrawDependsOnlyOnItsKey) {
  DelayDistribution d;
  ASSERT_TRUE(parse_delay_tail("uniform:10:120", d, nullptr));
  std::map<int, double> forward;
  for (int i = 0; i < 500; ++i) forward[i] = draw_delay(d, 3, i % 5, i / 5, i % 13).delay_s;
  for (int i = 499; i >= 0; --i)
    EXPECT_EQ(draw_delay(d, 3, i % 5, i / 5, i % 13).delay_s, forward[i]);
  // Another seed, day, train or station gives other draws.
  int same = 0;
  for (int i = 0; i < 500; ++i)
    same += draw_delay(d, 4, i % 5, i / 5, i % 13).delay_s == forward[i] && forward[i] > 0.0;
  EXPECT_LT(same, 5);
  for (int i = 0; i < 2000; ++i) {
    const DelayDraw x = draw_delay(d, 9, 0, i, 0);
    if (x.kind == DelayKind::Tail) {
      EXPECT_GT(x.delay_s, 10.0);
      EXPECT_LE(x.delay_s, 120.0);
    }
  }
  std::string why;
  EXPECT_FALSE(parse_delay_tail("uniform:5:120", d, &why));  // below the small range
  EXPECT_FALSE(parse_delay_tail("gamma:3", d, &why));
  EXPECT_FALSE(parse_delay_tail("exponential:-1", d, &why));
  EXPECT_NE(why.find("exponential:MEAN"), std::string::npos);
}

TEST(MonteCarlo, ADayWithoutDelaysCostsThePlansEnergyByAnIndependentEvaluation) {
  const Plan plan = small_plan({0.0, 98.0, 300.0, 398.0});
  const MonteCarlo mc(small_library(), plan, small_options(), small_runs());
  const DayRecord r = mc.plan_day();
  EXPECT_EQ(r.punctual, r.arrivals);
  EXPECT_EQ(r.arrivals, 12);
  EXPECT_EQ(r.lateness_sum_s, 0.0);
  EXPECT_EQ(r.knock_on_delays, 0);
  // Independent: every section re-solved for its planned time, each train's whole trip laid in
  // the fleet's power balance (energy/, exact bins of the whole trip on the same grid).
  const dp::SectionLibrary& lib = small_library();
  std::vector<dp::SectionTimeSolve> solves;
  for (std::size_t j = 0; j < lib.size(); ++j)
    solves.push_back(lib.solve(j, plan.running_time_s(0, j)));
  std::vector<const physics::SimulationResult*> sims;
  double traction_J = 0.0;
  for (const auto& s : solves) {
    sims.push_back(&s.search.run.sim);
    traction_J += s.search.run.sim.energy.traction_work_J;
  }
  const physics::Trip trip = fleet::trip_from_runs(lib, sims, {30.0, 30.0});
  const energy::PowerProfile profile(trip, 10, {});
  energy::PowerBalance balance({&profile, &profile, &profile, &profile}, 1200.0);
  balance.place_all({0, 98, 300, 398});
  const energy::FleetEnergy e = balance.energy();
  EXPECT_NEAR(r.traction_kJ, 4.0 * traction_J / 1e3, 1e-6 * r.traction_kJ);
  EXPECT_NEAR(r.traction_kJ, e.traction_J / 1e3, 1e-6 * r.traction_kJ);
  // A train leaves as the one ahead brakes into the next stop: they share energy, the check
  // is not empty.
  ASSERT_GT(e.used_regen_J, 0.01 * e.traction_J);
  // Sections start mid-bin on a whole trip's grid; here each is laid at its departure rounded
  // to 0.1 s: the used energy agrees within a small share.
  EXPECT_NEAR(r.used_regen_kJ, e.used_regen_J / 1e3, 0.02 * e.used_regen_J / 1e3);
  EXPECT_NEAR(r.substation_kJ, e.substation_J() / 1e3, 2e-3 * r.substation_kJ);
}

TEST(MonteCarlo, OneForcedDelayReproducesQuestion31sExactRecovery) {
  const Plan plan = small_plan({0.0, 900.0});
  MonteCarloOptions o = small_options();
  o.early_s = 0.0;  // question 3.1: no early departure
  const MonteCarlo mc(small_library(), plan, o, small_runs());
  DelayRecoveryOptions ro;
  ro.check_followers = false;
  const DelayRecoveryResult ref =
      recover_delay(small_library(), plan, 0, 0, 35.0, ro, test_store());
  ASSERT_EQ(ref.sections.size(), 2u);  // 35 s over two 20 s margins
  // The same times, section by section, re-applying the policy at each departure.
  const double dep0 = plan.trains[0].departure_s[0] + 35.0;
  const double t0 = mc.exact_time(0, 0, dep0);
  EXPECT_NEAR(t0, ref.sections[0].new_time_s, 0.01);
  const double dep1 = dep0 + t0 + 30.0;
  const double t1 = mc.exact_time(0, 1, dep1);
  EXPECT_NEAR(t1, ref.sections[1].new_time_s, 0.01);
  EXPECT_NEAR(dep1 + t1, plan.trains[0].arrival_s[2], 1e-6);  // back on time at A8 exactly
  // The day: one recovery ending at A8, and the extra traction of the recovery.
  const std::vector<ForcedDelay> forced = {{0, 0, 35.0}};
  const DayRecord day = mc.simulate_day(0, &forced);
  const DayRecord base = mc.plan_day();
  EXPECT_EQ(day.recoveries, 1);
  EXPECT_NEAR(day.recovery_time_sum_s, ref.sections.back().new_arrival_s - dep0, 0.02);
  EXPECT_EQ(day.punctual, day.arrivals - 1);  // A7 is 15 s late, A8 on time
  const double extra_ref = ref.summary.recovery_energy_kJ - ref.summary.plan_energy_kJ;
  const double extra_mc = day.traction_kJ - base.traction_kJ;
  ASSERT_GT(extra_ref, 1000.0);
  // The Monte Carlo blends runs 2 s apart: within 2 % of the re-solved recovery's extra energy.
  EXPECT_NEAR(extra_mc, extra_ref, 0.02 * extra_ref);
}

TEST(MonteCarlo, ExactRecoveryNeverCostsMoreTractionThanTheRule) {
  const Plan plan = small_plan({0.0, 130.0, 260.0, 400.0, 520.0});
  MonteCarloOptions exact = small_options(), rule = small_options();
  rule.recovery = RecoveryPolicy::Rule;
  exact.seed = rule.seed = 11;
  const MonteCarlo a(small_library(), plan, exact, small_runs());
  const MonteCarlo b(small_library(), plan, rule, small_runs());
  const auto da = a.run_days(0, 30, 2), db = b.run_days(0, 30, 2);
  int differ = 0;
  for (std::size_t i = 0; i < da.size(); ++i) {
    EXPECT_EQ(da[i].primary_delays, db[i].primary_delays);  // common random numbers
    EXPECT_LE(da[i].traction_kJ, db[i].traction_kJ * (1.0 + 1e-9)) << "day " << i;
    differ += da[i].traction_kJ < db[i].traction_kJ * (1.0 - 1e-6);
  }
  EXPECT_GT(differ, 0);  // the comparison is not empty
}

TEST(MonteCarlo, StatisticsAreTheSameBytesForAnyThreadsAndShards) {
  const Plan plan = small_plan({0.0, 130.0, 260.0, 400.0});
  MonteCarloOptions o = small_options();
  o.seed = 5;
  const MonteCarlo mc(small_library(), plan, o, small_runs());
  auto as_json = [&](std::vector<DayRecord> days) {
    MonteCarloRun run;
    run.config = {{"days", 24}, {"seed", 5}};
    run.stations = plan.stations;
    run.histogram = pooled_histogram(days);
    run.days = std::move(days);
    run.plan_energy = {{"traction_kJ", 1.0}};
    return run;
  };
  const std::string one = run_json(as_json(mc.run_days(0, 24, 1)), "").dump();
  const std::string two = run_json(as_json(mc.run_days(0, 24, 2)), "").dump();
  EXPECT_EQ(one, two);
  const auto [f1, l1] = shard_days(24, 1, 2);
  const auto [f2, l2] = shard_days(24, 2, 2);
  EXPECT_EQ(l1, f2);
  const MonteCarloRun s1 = run_from_json(run_json(as_json(mc.run_days(f1, l1, 2)), "1/2"));
  const MonteCarloRun s2 = run_from_json(run_json(as_json(mc.run_days(f2, l2, 1)), "2/2"));
  EXPECT_EQ(run_json(merge_runs({s2, s1}), "").dump(), one);
  EXPECT_THROW(merge_runs({s1}), std::invalid_argument);          // days missing
  EXPECT_THROW(merge_runs({s1, s1, s2}), std::invalid_argument);  // days repeated
}

TEST(MonteCarlo, RunningThePlanEarlyIsABufferThatCostsNoPlanEnergy) {
  const Plan plan = small_plan({0.0, 98.0, 300.0});
  MonteCarloOptions early = small_options();
  early.run_early_s = 10.0;
  const MonteCarlo a(small_library(), plan, small_options(), small_runs());
  const MonteCarlo b(small_library(), plan, early, small_runs());
  const DayRecord pa = a.plan_day(), pb = b.plan_day();
  // Every train 10 s early: the same runs, the same overlaps (the grid shifts by whole bins).
  EXPECT_EQ(pa.traction_kJ, pb.traction_kJ);
  EXPECT_NEAR(pa.substation_kJ, pb.substation_kJ, 1e-9 * pa.substation_kJ);
  EXPECT_EQ(pb.punctual, pb.arrivals);
  // An 8 s delay leaves the early-running train still 2 s ahead of the timetable: no lateness;
  // the train on time to the timetable is 8 s late at the next stop's arrival, unless recovered.
  const std::vector<ForcedDelay> forced = {{1, 0, 8.0}};
  const DayRecord db = b.simulate_day(0, &forced);
  EXPECT_EQ(db.lateness_sum_s, 0.0);
  EXPECT_EQ(db.punctual, db.arrivals);
  EXPECT_EQ(db.recoveries, 1);  // it still returns to its operating plan
  const std::vector<ForcedDelay> forced_late = {{1, 0, 30.0}};
  const DayRecord da = a.simulate_day(0, &forced_late), dl = b.simulate_day(0, &forced_late);
  EXPECT_GT(da.lateness_sum_s, dl.lateness_sum_s + 9.0);  // 10 s less at the first stop
}

TEST(MonteCarlo, PunctualCapsKeepArrivalsOnTheWayPunctualAtLeastEnergy) {
  // 25 s late at A6, 20 s margins: flat out reaches A7 5 s late, so the recovery station is A8.
  // The exact split spreads the lateness (A7 about 12 s late: not punctual); with punctual caps
  // A7 is reached exactly 10 s late, A8 on time; the rule reaches A7 5 s late.
  const Plan plan = small_plan({0.0, 900.0});
  MonteCarloOptions exact = small_options(), capped = small_options(), rule = small_options();
  capped.recovery = RecoveryPolicy::ExactPunctual;
  rule.recovery = RecoveryPolicy::Rule;
  const std::vector<ForcedDelay> forced = {{0, 0, 25.0}};
  const DayRecord de =
      MonteCarlo(small_library(), plan, exact, small_runs()).simulate_day(0, &forced);
  const DayRecord dc =
      MonteCarlo(small_library(), plan, capped, small_runs()).simulate_day(0, &forced);
  const DayRecord dr =
      MonteCarlo(small_library(), plan, rule, small_runs()).simulate_day(0, &forced);
  EXPECT_EQ(de.punctual, de.arrivals - 1);
  EXPECT_EQ(dc.punctual, dc.arrivals);
  EXPECT_EQ(dr.punctual, dr.arrivals);
  EXPECT_NEAR(dc.max_lateness_s, 10.0, 1e-6);
  EXPECT_GT(de.max_lateness_s, 10.5);
  EXPECT_NEAR(dr.max_lateness_s, 5.0, 1e-3);
  // Energy: the exact split, then the capped one, then the rule.
  EXPECT_LT(de.traction_kJ, dc.traction_kJ);
  EXPECT_LT(dc.traction_kJ, dr.traction_kJ);
}

TEST(MonteCarloStatistics, ConfidenceIntervalIsTheStudentInterval) {
  const Estimate e = estimate({1.0, 2.0, 3.0, 4.0});
  EXPECT_DOUBLE_EQ(e.mean, 2.5);
  EXPECT_NEAR(e.sd, std::sqrt(5.0 / 3.0), 1e-12);
  EXPECT_NEAR(e.ci95, 3.182 * std::sqrt(5.0 / 3.0) / 2.0, 1e-12);
  EXPECT_NEAR(t_quantile_975(1000), 1.962339, 2e-5);  // tables: 1.962339
  EXPECT_NEAR(t_quantile_975(40), 2.021075, 2e-4);
}

}  // namespace
}  // namespace ecorail::recovery
