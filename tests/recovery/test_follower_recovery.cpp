// A held-up follower driven back on time (recover_delay's followers, service/follower.hpp with
// the recovery of recovery/knock_on.cpp), against a brute force over the same model on A6 -> A9
// (two trains, each section planned 20 s above its flat-out run, 30 s dwells): every
// combination of section running times on a 1 s grid (flat out to 30 s above it, and the
// planned time), each section the energy-optimal run for its time, leaving each stop when ready
// (its planned departure, or its arrival plus the least dwell) or, where that run would come
// closer than its braking distance to the train ahead, after the least wait that keeps it
// (computed here from the leader's own time_at, not by the model's code). Lexicographic, as the
// late train's recovery: back on time at the earliest station, then the least traction energy.
// The follower must do no worse than the best combination. Also: the lateness-first mode never
// has more total lateness than the energy-first one, drives the late train flat out up to the
// last section before its recovery station, and every run keeps its braking distance.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "recovery/delay_recovery.hpp"
#include "recovery_fixture.hpp"
#include "service/separation.hpp"

namespace ecorail::recovery {
namespace {

using testing::small_library;
using testing::small_plan;
using testing::test_store;

constexpr double kLate_s = 0.05;  // an arrival later than this is late

// The least wait after ready_s for which `run` (section k's run from rest) keeps
// gap >= v^2 / 2b behind the leader at every trace point (the leader leaves the line at its
// last arrival).
double least_wait_s(const physics::Trip& leader, const physics::SimulationResult& run,
                    double section_start_m, double ready_s, double b) {
  auto clear_at = [&](double position_m) {
    return position_m >= leader.length_m() ? leader.arrival_s() : leader.time_at(position_m);
  };
  double need = clear_at(section_start_m) - ready_s;
  for (const physics::TracePoint& p : run.trace)
    need = std::max(
        need, clear_at(section_start_m + p.s_m + p.v_ms * p.v_ms / (2.0 * b)) - (ready_s + p.t_s));
  return std::max(0.0, need);
}

struct Leaf {
  int back_at = 0;                // station index where back on time (after the last late arrival)
  double lateness_sum_s = 0.0;    // sum of arrival lateness
  double final_lateness_s = 0.0;  // at the last stop
  double energy_J = 0.0;
};

// Every combination of the follower's running times on the grid of the model's candidates:
// flat out, then every `step` s below the planned time + `slower`, that time itself, and the
// planned time; each leaf of the enumeration is one whole run of the follower.
std::vector<Leaf> brute_force(const Plan& plan, std::size_t f, const physics::Trip& leader,
                              double b, double step, double slower) {
  const dp::SectionLibrary& lib = small_library();
  const std::size_t n = lib.size();
  std::vector<std::vector<physics::SimulationResult>> runs(n);
  std::vector<double> starts(n, 0.0);
  for (std::size_t k = 0; k < n; ++k) {
    runs[k].push_back(lib.min_time_run(k));
    const double top = plan.running_time_s(f, k) + slower;
    for (int j = 1; lib.min_time_s(k) + step * j < top - 1e-6; ++j)
      runs[k].push_back(lib.solve(k, std::round((lib.min_time_s(k) + step * j) * 1000.0) / 1000.0)
                            .search.run.sim);
    runs[k].push_back(lib.solve(k, std::round(top * 1000.0) / 1000.0).search.run.sim);
    runs[k].push_back(lib.solve(k, plan.running_time_s(f, k)).search.run.sim);
    if (k > 0) starts[k] = starts[k - 1] + lib.route(k - 1).length_m();
  }
  const TrainStops& st = plan.trains[f];
  std::vector<Leaf> leaves;
  std::vector<double> late(n + 1, 0.0);
  auto visit = [&](auto&& self, std::size_t k, double ready, double energy) -> void {
    if (k == n) {
      Leaf leaf;
      leaf.energy_J = energy;
      leaf.final_lateness_s = late[n];
      for (std::size_t j = 1; j <= n; ++j) {
        if (late[j] > kLate_s) leaf.back_at = static_cast<int>(j) + 1;
        leaf.lateness_sum_s += std::max(0.0, late[j]);
      }
      leaves.push_back(leaf);
      return;
    }
    for (const physics::SimulationResult& r : runs[k]) {
      // A wait is rounded up by 0.05 s and then to 0.01 s, as the model rounds it.
      const double w = least_wait_s(leader, r, starts[k], ready, b);
      const double dep = w > 0.0 ? ready + std::ceil((w + 0.05) * 100.0) / 100.0 : ready;
      const double arr = dep + r.running_time_s;
      late[k + 1] = arr - st.arrival_s[k + 1];
      const double next =
          k + 1 < n ? std::max(st.departure_s[k + 1], arr + std::min(30.0, plan.dwell_s(f, k + 1)))
                    : arr;
      self(self, k + 1, next, energy + r.energy.traction_work_J);
    }
  };
  visit(visit, 0, st.departure_s[0], 0.0);
  return leaves;
}

int back_on_time_index(const std::vector<double>& lateness_s) {
  int back = 0;
  for (std::size_t j = 1; j < lateness_s.size(); ++j)
    if (lateness_s[j] > kLate_s) back = static_cast<int>(j) + 1;
  return back;
}

struct DelayCase {
  double headway_s, delay_s;
  std::size_t station;
  bool lateness_first;
};

TEST(FollowerRecovery, AHeldUpFollowerIsTheOptimumOfABruteForceOverItsRunningTimes) {
  const double b = service::default_separation_braking_m_s2(small_library().train());
  for (const DelayCase c : {DelayCase{60.0, 50.0, 0, false}, DelayCase{50.0, 30.0, 1, true}}) {
    SCOPED_TRACE("headway " + std::to_string(c.headway_s) + " s, delay " +
                 std::to_string(c.delay_s) + " s at station " + std::to_string(c.station) +
                 (c.lateness_first ? ", lateness first" : ", energy first"));
    const Plan plan = small_plan({0.0, c.headway_s});
    DelayRecoveryOptions o;
    o.max_followers = 1;
    o.lateness_first = c.lateness_first;
    o.follower_time_step_s = 5.0;  // a coarse grid keeps the enumeration short
    o.follower_slower_s = 5.0;
    const DelayRecoveryResult r =
        recover_delay(small_library(), plan, 0, c.station, c.delay_s, o, test_store());
    ASSERT_EQ(r.followers.size(), 1u);
    ASSERT_TRUE(r.followers[0].affected);
    ASSERT_EQ(r.train_trips.size(), 2u);
    const std::vector<Leaf> leaves =
        brute_force(plan, 1, r.train_trips[0], b, o.follower_time_step_s, o.follower_slower_s);
    // The enumeration's optimum, by the model's objective.
    double least = 1e300, best_energy = 1e300;
    for (const Leaf& l : leaves)
      least = std::min(least, c.lateness_first ? l.lateness_sum_s : l.back_at);
    // Energy first: back on time earliest, then the least final lateness, then least energy.
    double least_final = 1e300;
    for (const Leaf& l : leaves)
      if (l.back_at == least) least_final = std::min(least_final, l.final_lateness_s);
    for (const Leaf& l : leaves)
      if (c.lateness_first
              ? l.lateness_sum_s <= least + kLate_s
              : l.back_at == least && l.final_lateness_s <= std::max(least_final, 0.0) + kLate_s)
        best_energy = std::min(best_energy, l.energy_J);
    const FollowerCheck& f = r.followers[0];
    if (c.lateness_first)
      EXPECT_LE(f.lateness_sum_s, least + kLate_s);
    else
      EXPECT_EQ(back_on_time_index(r.trains[1].lateness_s), least);
    EXPECT_LE(f.traction_kJ * 1e3, best_energy * (1.0 + 1e-6));
    EXPECT_GE(f.traction_kJ * 1e3, best_energy * (1.0 - 1e-3));  // the same grid: no better
    EXPECT_GE(f.min_distance_margin_m, -0.01);
    // Driven, it is late for no longer than when it only waits and runs its plan.
    DelayRecoveryOptions wait = o;
    wait.recover_followers = false;
    const DelayRecoveryResult w =
        recover_delay(small_library(), plan, 0, c.station, c.delay_s, wait, test_store());
    ASSERT_EQ(w.followers.size(), 1u);
    if (c.lateness_first)
      EXPECT_LE(f.lateness_sum_s, w.followers[0].lateness_sum_s + kLate_s);
    else
      EXPECT_LE(back_on_time_index(r.trains[1].lateness_s),
                back_on_time_index(w.trains[1].lateness_s));
  }
}

TEST(FollowerRecovery, LatenessFirstHasNoMoreTotalLatenessAndRunsFlatOutBeforeTheLastSection) {
  const Plan plan = small_plan({0.0, 50.0});
  DelayRecoveryOptions o;
  o.max_followers = 1;
  o.lateness_first = true;
  const DelayRecoveryResult r = recover_delay(small_library(), plan, 0, 0, 30.0, o, test_store());
  DelayRecoveryOptions e = o;
  e.lateness_first = false;
  const DelayRecoveryResult x = recover_delay(small_library(), plan, 0, 0, 30.0, e, test_store());
  EXPECT_EQ(r.summary.recovery_mode, "lateness-first");
  EXPECT_EQ(x.summary.recovery_mode, "energy-first");
  // The same energy-first run, reported beside.
  EXPECT_NEAR(r.summary.energy_first_total_lateness_s, x.summary.total_lateness_s, 1e-9);
  EXPECT_NEAR(r.summary.energy_first_energy_kJ, x.summary.recovery_energy_kJ, 1e-9);
  // Here the difference is real: the follower is held up less behind a train that hurries.
  EXPECT_LT(r.summary.total_lateness_s, x.summary.total_lateness_s - 1.0);
  EXPECT_GE(r.summary.recovery_energy_kJ, x.summary.recovery_energy_kJ);
  EXPECT_EQ(r.summary.back_on_time_at, x.summary.back_on_time_at);
  ASSERT_GE(r.sections.size(), 2u);
  for (std::size_t k = 0; k + 1 < r.sections.size(); ++k)
    EXPECT_TRUE(r.sections[k].flat_out) << "section " << k;
  // The last section is no faster than flat out and no slower than the rule's, which closes it.
  const RecoverySection& last = r.sections.back();
  EXPECT_GE(last.new_time_s, last.min_time_s - 1e-6);
  EXPECT_LE(last.new_time_s, last.rule_time_s + 1e-3);
  // The late train is back on time (re-simulated).
  const int e_idx = plan.station_index(r.summary.back_on_time_at);
  EXPECT_LE(last.new_arrival_s, plan.trains[0].arrival_s[static_cast<std::size_t>(e_idx)] + 0.05);
  // Every driven run keeps its braking distance (the model's scan, re-simulated).
  for (const FollowerCheck& f : r.followers) EXPECT_GE(f.min_distance_margin_m, -0.01);
}

TEST(FollowerRecovery, WithNobodyHeldUpLatenessFirstIsTheRule) {
  const Plan plan = small_plan({0.0, 600.0});
  DelayRecoveryOptions o;
  o.lateness_first = true;
  const DelayRecoveryResult r = recover_delay(small_library(), plan, 0, 0, 35.0, o, test_store());
  ASSERT_EQ(r.summary.followers_affected, 0);
  for (const RecoverySection& s : r.sections) EXPECT_NEAR(s.new_time_s, s.rule_time_s, 1e-3);
  EXPECT_NEAR(r.summary.recovery_energy_kJ, r.summary.rule_energy_kJ, 1e-6);
  EXPECT_GE(r.summary.recovery_energy_kJ, r.summary.energy_first_energy_kJ * (1.0 - 1e-4));
}

}  // namespace
}  // namespace ecorail::recovery
