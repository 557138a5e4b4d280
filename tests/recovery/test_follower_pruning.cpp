// The held-up follower's dynamic programme (service::follower_path) drops states by bounds
// (FollowerRecovery::prune): a pessimistically timed whole path bounds the least lateness, and a
// state that can no longer reach it is never chosen. Here the pruned programme is compared with
// the plain Pareto programme (every non-dominated state kept, itself checked against a brute
// force in test_follower_recovery.cpp) on random cases of a six-section line (the small line's
// three sections run twice), both objectives: the same runs, departures, lateness and energy.
// The lazy programme (candidate runs solved only where a kept state would drive them) is
// compared with the one given every run up front in the same way.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <random>

#include "recovery_fixture.hpp"
#include "service/follower.hpp"
#include "service/separation.hpp"

namespace ecorail::recovery {
namespace {

using testing::small_library;

constexpr std::size_t kSections = 6;

const physics::SimulationResult& run_for(std::size_t k, double time_s) {
  static std::map<std::pair<std::size_t, long long>, physics::SimulationResult> runs;
  const dp::SectionLibrary& lib = small_library();
  const std::size_t s = k % lib.size();
  const long long ms = std::llround(time_s * 1000.0);
  auto it = runs.find({s, ms});
  if (it == runs.end()) {
    physics::SimulationResult sim = time_s <= lib.min_time_s(s) + 1e-6
                                        ? lib.min_time_run(s)
                                        : lib.solve(s, ms / 1000.0).search.run.sim;
    it = runs.emplace(std::make_pair(s, ms), std::move(sim)).first;
  }
  return it->second;
}

physics::Trip trip_of(const std::vector<const physics::SimulationResult*>& runs,
                      const std::vector<double>& dwell_after_s, double departure_s) {
  const dp::SectionLibrary& lib = small_library();
  std::vector<physics::TripSection> sections;
  for (std::size_t k = 0; k < runs.size(); ++k)
    sections.push_back({&lib.route(k % lib.size()), runs[k], dwell_after_s[k]});
  return physics::Trip(sections, departure_s, lib.train().regen_efficiency);
}

// One random case: the follower's plan (each section 8, 11 or 14 s above flat out, 30 s
// dwells), its candidates (flat out, then every 3 s up to 4 s above the planned time; the runs
// repeat between sections and trials, so few are solved) and the train ahead (the same plan,
// headway 70 to 110 s, held 20 to 140 s at a random stop).
struct Case {
  service::ServicePlan plan;
  std::vector<std::vector<const physics::SimulationResult*>> cands;
  std::vector<std::vector<double>> cand_times_s;
  physics::Trip leader, planned;
  double headway_s = 0.0;
};

Case make_case(std::mt19937& rng) {
  const dp::SectionLibrary& lib = small_library();
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  Case x;
  x.cands.resize(kSections);
  x.cand_times_s.resize(kSections);
  std::vector<const physics::SimulationResult*> planned_runs;
  for (std::size_t k = 0; k < kSections; ++k) {
    const double t_min = lib.min_time_s(k % lib.size());
    const double t = t_min + 8.0 + 3.0 * std::floor(3.0 * unit(rng));
    x.plan.runs.push_back(run_for(k, t));
    planned_runs.push_back(&run_for(k, t));
    for (double c = t_min; c < t + 4.0 - 1e-6; c += 3.0) x.cand_times_s[k].push_back(c);
    x.cand_times_s[k].push_back(t + 4.0);
    for (double c : x.cand_times_s[k]) x.cands[k].push_back(&run_for(k, c));
    if (k + 1 < kSections) x.plan.dwells_s.push_back(30.0);
  }
  std::vector<double> dwell_after = x.plan.dwells_s;
  dwell_after.push_back(0.0);
  x.plan.trip = trip_of(planned_runs, dwell_after, 0.0);
  x.headway_s = 70.0 + 40.0 * unit(rng);
  std::vector<double> leader_dwell = dwell_after;
  const auto at = static_cast<std::size_t>(unit(rng) * (kSections - 1));
  leader_dwell[at] += 20.0 + 120.0 * unit(rng);
  x.leader = trip_of(planned_runs, leader_dwell, 0.0);
  x.planned = x.plan.trip.shifted(x.headway_s);
  return x;
}

TEST(FollowerPruning, ThePrunedProgrammeChoosesThePathOfThePlainOne) {
  const dp::SectionLibrary& lib = small_library();
  const double b = service::default_separation_braking_m_s2(lib.train());
  const double room =
      service::SeparationOptions().train_length_m + service::SeparationOptions().safety_margin_m;
  std::mt19937 rng(7);
  int held_up = 0;
  for (int trial = 0; trial < 12; ++trial) {
    SCOPED_TRACE("trial " + std::to_string(trial));
    const Case x = make_case(rng);
    const service::ServicePlan& plan = x.plan;
    const auto& cands = x.cands;
    const physics::Trip& leader = x.leader;
    const physics::Trip& planned = x.planned;
    const double headway = x.headway_s;
    for (const bool lateness_first : {false, true}) {
      SCOPED_TRACE(lateness_first ? "lateness first" : "energy first");
      service::FollowerRecovery recovery;
      recovery.min_dwell_s.assign(kSections + 1, 20.0);
      recovery.lateness_first = lateness_first;
      recovery.runs = [&](std::size_t first) {
        return std::vector<std::vector<const physics::SimulationResult*>>(
            cands.begin() + static_cast<long>(first), cands.end());
      };
      service::FollowerRecovery plain = recovery;
      plain.prune = false;
      const auto pruned =
          service::follower_path(plan, leader, planned, b, room, recovery, 0, 0, headway);
      const auto full =
          service::follower_path(plan, leader, planned, b, room, plain, 0, 0, headway);
      ASSERT_EQ(pruned.size(), full.size());
      double energy_pruned = 0.0, energy_full = 0.0;
      for (std::size_t k = 0; k < kSections; ++k) {
        SCOPED_TRACE("section " + std::to_string(k));
        EXPECT_EQ(pruned[k].run, full[k].run);
        EXPECT_NEAR(pruned[k].departure_s, full[k].departure_s, 1e-9);
        EXPECT_NEAR(pruned[k].line_wait_s, full[k].line_wait_s, 1e-9);
        energy_pruned += pruned[k].run->energy.traction_work_J;
        energy_full += full[k].run->energy.traction_work_J;
        if (full[k].line_wait_s > 0.0) ++held_up;
      }
      EXPECT_NEAR(energy_pruned, energy_full, 1e-9 * energy_full);
      const double arrival_pruned = pruned.back().departure_s + pruned.back().run->running_time_s;
      const double arrival_full = full.back().departure_s + full.back().run->running_time_s;
      EXPECT_NEAR(arrival_pruned, arrival_full, 1e-9);
    }
  }
  EXPECT_GT(held_up, 12);  // the cases do hold the follower up
}

// Lazy candidates (FollowerRecovery::run_times and solve): the programme asks only for the
// runs some kept state would drive, with bounds from their times; on random cases, both
// objectives, it chooses the same runs, departures and waits as with every run given up front,
// asks for fewer runs in all, and never asks for a run twice. With no slack (a run may be up to
// the solver's tolerance faster than its time, so a bound can be contradicted) the answer is
// the same too (the programme then solves every candidate and runs again), and so it is when
// some runs are at hand from the start (held).
TEST(FollowerPruning, TheLazyProgrammeChoosesThePathOfTheEagerOne) {
  const dp::SectionLibrary& lib = small_library();
  const double b = service::default_separation_braking_m_s2(lib.train());
  const double room =
      service::SeparationOptions().train_length_m + service::SeparationOptions().safety_margin_m;
  std::mt19937 rng(11);
  std::size_t asked = 0, candidates = 0;
  int held_up = 0;
  for (int trial = 0; trial < 10; ++trial) {
    SCOPED_TRACE("trial " + std::to_string(trial));
    const Case x = make_case(rng);
    for (std::size_t k = 0; k < kSections; ++k) candidates += 4 * x.cands[k].size();
    for (const bool lateness_first : {false, true})
      for (const double slack : {dp::kTimeTolerance_s + 0.002, 0.0, -1.0}) {
        // -1: slack as the first, and every other candidate's run at hand (held) from the start.
        const bool with_held = slack < 0.0;
        SCOPED_TRACE(lateness_first ? "lateness first" : "energy first");
        SCOPED_TRACE("slack " + std::to_string(slack));
        service::FollowerRecovery eager;
        eager.min_dwell_s.assign(kSections + 1, 20.0);
        eager.lateness_first = lateness_first;
        eager.runs = [&](std::size_t first) {
          return std::vector<std::vector<const physics::SimulationResult*>>(
              x.cands.begin() + static_cast<long>(first), x.cands.end());
        };
        service::FollowerRecovery lazy = eager;
        lazy.runs = nullptr;
        lazy.run_time_slack_s = with_held ? dp::kTimeTolerance_s + 0.002 : slack;
        if (with_held)
          lazy.held = [&](std::size_t k, double t) -> const physics::SimulationResult* {
            return std::llround(t * 1000.0) % 2000 < 1000 ? &run_for(k, t) : nullptr;
          };
        lazy.run_times = [&](std::size_t first) {
          return std::vector<std::vector<double>>(x.cand_times_s.begin() + static_cast<long>(first),
                                                  x.cand_times_s.end());
        };
        std::map<std::pair<std::size_t, long long>, int> times_asked;
        lazy.solve = [&](std::size_t k, const std::vector<double>& times_s) {
          std::vector<const physics::SimulationResult*> out;
          for (double t : times_s) {
            ++times_asked[{k, std::llround(t * 1000.0)}];
            out.push_back(&run_for(k, t));
          }
          return out;
        };
        const auto want =
            service::follower_path(x.plan, x.leader, x.planned, b, room, eager, 0, 0, x.headway_s);
        const auto got =
            service::follower_path(x.plan, x.leader, x.planned, b, room, lazy, 0, 0, x.headway_s);
        ASSERT_EQ(got.size(), want.size());
        for (std::size_t k = 0; k < kSections; ++k) {
          SCOPED_TRACE("section " + std::to_string(k));
          EXPECT_EQ(got[k].run, want[k].run);
          EXPECT_EQ(got[k].departure_s, want[k].departure_s);
          EXPECT_EQ(got[k].ready_s, want[k].ready_s);
          EXPECT_EQ(got[k].line_wait_s, want[k].line_wait_s);
          if (want[k].line_wait_s > 0.0) ++held_up;
        }
        if (slack != 0.0) {
          for (const auto& [key, count] : times_asked) {
            EXPECT_EQ(count, 1) << "section " << key.first << ", " << key.second << " ms";
            ++asked;
          }
        }
      }
  }
  EXPECT_GT(held_up, 10);        // the cases do hold the follower up
  EXPECT_LT(asked, candidates);  // the lazy programme solved fewer runs in all
}

// The shortcuts under the programme give the plain answers bit for bit: time_at searched from a
// hint, and the clear time from blocks made beforehand (any block size).
TEST(FollowerPruning, HintedSearchAndKeptBlocksGiveTheSameTimes) {
  const dp::SectionLibrary& lib = small_library();
  const double b = service::default_separation_braking_m_s2(lib.train());
  const double room = 150.0;
  std::vector<const physics::SimulationResult*> runs;
  for (std::size_t k = 0; k < kSections; ++k)
    runs.push_back(&run_for(k, lib.min_time_s(k % lib.size()) + 8.0));
  const physics::Trip leader = trip_of(runs, {30, 90, 30, 30, 30, 0}, 40.0);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> along(0.0, leader.length_m());
  std::size_t hint = 0;
  for (int i = 0; i < 2000; ++i) {
    // Jumps and small steps, forwards and back.
    const double x = i % 3 == 0 ? along(rng) : std::min(leader.length_m(), along(rng) * 1e-3 + i);
    ASSERT_EQ(leader.time_at(x, &hint), leader.time_at(x)) << x;
  }
  for (std::size_t k = 0; k < kSections; ++k)
    for (const double extra : {0.0, 3.0, 12.0}) {
      const physics::SimulationResult& run = run_for(k, lib.min_time_s(k % lib.size()) + extra);
      const double start = leader.section_start_m(k);
      const double plain = service::clear_from_s(leader, run, start, b, room);
      for (const std::size_t block : {1, 16, 32, 1000})
        EXPECT_EQ(service::clear_from_s(leader, run, start, b, room,
                                        service::reach_blocks(run, b, room, block)),
                  plain);
    }
}

}  // namespace
}  // namespace ecorail::recovery
