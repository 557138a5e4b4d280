// Per-train patterns on the small fleet. The pricing of a pattern change without touching the
// balance (PowerBalance::substation_change_if) equals the change a fresh balance shows; the
// per-train stage is never worse than one pattern for all, keeps every train's dwells in range
// and its trip time, gives the same result for one and two threads, and leaves every train at a
// local optimum: no single one-second move of one train's own pattern, re-solved and evaluated
// here from scratch, lowers the substation energy.
#include <gtest/gtest.h>

#include <cstdio>
#include <map>
#include <memory>

#include "energy/fleet_energy_model.hpp"
#include "fleet/pattern_search.hpp"
#include "fleet_fixture.hpp"

namespace ecorail::fleet {
namespace {

// Trips of patterns from section solves kept by (section, running time): the local-optimality
// check below re-solves only the sections a move changes.
class TripMemo {
 public:
  explicit TripMemo(const dp::SectionLibrary& lib) : lib_(lib) {}
  physics::Trip trip(const FleetPattern& p) {
    std::vector<const physics::SimulationResult*> runs;
    for (std::size_t i = 0; i < lib_.size(); ++i) {
      const auto key = std::make_pair(i, p.running_times_s[i]);
      auto it = solves_.find(key);
      if (it == solves_.end()) it = solves_.emplace(key, lib_.solve(i, key.second)).first;
      EXPECT_TRUE(it->second.search.converged);
      runs.push_back(&it->second.search.run.sim);
    }
    return trip_from_runs(lib_, runs, p.dwells_s);
  }

 private:
  const dp::SectionLibrary& lib_;
  std::map<std::pair<std::size_t, double>, dp::SectionTimeSolve> solves_;
};

// The fleet's substation energy with train k on its own trip, from a balance built afresh.
double fresh_substation_J(const TestFleet& models, const std::vector<physics::Trip>& trips,
                          const std::vector<int>& departures_s) {
  std::vector<std::unique_ptr<PowerProfile>> own;
  std::vector<const PowerProfile*> profiles;
  for (const physics::Trip& t : trips) {
    own.push_back(make_profile(t, models.options()));
    profiles.push_back(own.back().get());
  }
  auto balance = models.make_balance(profiles);
  balance->place_all(departures_s);
  return balance->energy().substation_J();
}

TEST(PerTrainPatterns, PricingWithoutChangeEqualsFreshBalance) {
  const FleetProblem problem = [] {
    FleetProblem p = testing::small_fleet(4, 150, 250, 600);
    p.trip_time_s = 480.0;
    return p;
  }();
  EnergyModelOptions model;
  model.time_step_s = 0.1;
  const auto& lib = testing::small_library();
  const TestFleet models(testing::small_pattern().trip, problem, model);
  const std::vector<int> departures = {0, 170, 400, 600};
  FleetPattern other = testing::small_pattern().pattern;
  other.dwells_s[0] += 3.0;
  other.running_times_s[1] -= 3.0;
  const PatternTrip changed = pattern_trip(lib, other);
  const auto candidate = make_profile(changed.trip, model);
  for (int k = 0; k < problem.trains; ++k) {
    auto balance = models.make_balance();
    balance->place_all(departures);
    const MicroJoules before = balance->traction() - balance->used();
    const MicroJoules priced = balance->substation_change_if(k, *candidate);
    balance->set_profile(k, candidate.get());
    EXPECT_EQ(balance->traction() - balance->used() - before, priced) << "train " << k;
    EXPECT_EQ(balance->used(), balance->recount_used());
    std::vector<physics::Trip> trips(problem.trains, testing::small_pattern().trip);
    trips[k] = changed.trip;
    EXPECT_NEAR(balance->energy().substation_J(), fresh_substation_J(models, trips, departures),
                1e-6);
  }
}

TEST(PerTrainPatterns, NeverWorseFeasibleDeterministicAndLocallyOptimal) {
  FleetProblem problem = testing::small_fleet(4, 150, 250, 600);
  problem.trip_time_s = 480.0;
  EnergyModelOptions model;
  model.time_step_s = 0.1;
  PatternSearchOptions o;
  o.headways.moves_per_run = 3000;
  o.deltas_s = {2.0, 1.0};
  o.per_train_patterns = true;
  o.headways.threads = 1;
  const auto& lib = testing::small_library();
  const PatternSearchResult r = optimise_pattern(lib, problem, model, testing::small_pattern(), o);
  o.headways.threads = 2;
  const PatternSearchResult r2 = optimise_pattern(lib, problem, model, testing::small_pattern(), o);
  ASSERT_FALSE(r.time_limit_reached);
  ASSERT_EQ(r.per_train.size(), static_cast<std::size_t>(problem.trains));
  EXPECT_EQ(r.timetable.evaluation.total.substation_J(),
            r2.timetable.evaluation.total.substation_J());
  for (int k = 0; k < problem.trains; ++k) {
    EXPECT_EQ(r.per_train[k].running_times_s, r2.per_train[k].running_times_s);
    EXPECT_EQ(r.per_train[k].dwells_s, r2.per_train[k].dwells_s);
  }
  const double common = r.common_pattern.total.substation_J();
  const double final_J = r.timetable.evaluation.total.substation_J();
  EXPECT_LE(final_J, common + 1e-6);
  EXPECT_LE(common, r.headways_only.total.substation_J() + 1e-6);

  // Every train's pattern is feasible, its trip runs that pattern (stop by stop), and the trips
  // laid in a balance built afresh give the reported energy. A train the search moved runs
  // exactly the section solves of its pattern (re-solved here).
  const std::vector<int>& t = r.timetable.evaluation.departures_s;
  const TestFleet models(r.pattern.trip, problem, model);
  TripMemo memo(lib);
  const std::vector<physics::Trip>& trips = r.per_train_trips;
  ASSERT_EQ(trips.size(), r.per_train.size());
  int moved_trains = 0;
  for (std::size_t k = 0; k < trips.size(); ++k) {
    const FleetPattern& p = r.per_train[k];
    for (double d : p.dwells_s) {
      EXPECT_GE(d, problem.dwell_min_s);
      EXPECT_LE(d, problem.dwell_max_s);
    }
    EXPECT_NEAR(p.trip_time_s(), problem.trip_time_s, 0.05);
    const auto stops = trips[k].stops();
    for (std::size_t j = 0; j + 1 < stops.size(); ++j) {
      EXPECT_NEAR(stops[j + 1].arrival_s - stops[j].departure_s, p.running_times_s[j], 0.05);
      if (j + 1 < p.running_times_s.size()) {
        EXPECT_NEAR(stops[j + 1].departure_s - stops[j + 1].arrival_s, p.dwells_s[j], 1e-9);
      }
    }
    EXPECT_NEAR(stops.back().arrival_s, problem.trip_time_s, 0.05);
    if (p.running_times_s != r.pattern.pattern.running_times_s ||
        p.dwells_s != r.pattern.pattern.dwells_s) {
      ++moved_trains;
      const auto resolved = make_profile(memo.trip(p), model);
      const auto reported = make_profile(trips[k], model);
      EXPECT_EQ(resolved->traction_total(), reported->traction_total()) << "train " << k;
      EXPECT_EQ(resolved->regen_total(), reported->regen_total()) << "train " << k;
    }
  }
  const double fresh = fresh_substation_J(models, trips, t);
  EXPECT_NEAR(fresh, final_J, 1e-6);
  EXPECT_GT(moved_trains, 0);  // the stage does something on this instance
  std::printf("per-train stage: %d of %d trains re-timed, %.1f kJ below one pattern\n",
              moved_trains, problem.trains, (common - final_J) / 1e3);

  // Local optimality of each train's own pattern against one-second moves.
  const std::size_t n = lib.size();
  int checked = 0;
  for (int k = 0; k < problem.trains; ++k) {
    for (std::size_t j = 0; j + 1 < n; ++j) {
      for (std::size_t i : {j, j + 1}) {
        for (double sign : {+1.0, -1.0}) {
          FleetPattern p = r.per_train[k];
          p.dwells_s[j] += sign;
          p.running_times_s[i] -= sign;
          if (p.dwells_s[j] < problem.dwell_min_s || p.dwells_s[j] > problem.dwell_max_s) continue;
          std::vector<physics::Trip> moved = trips;
          moved[k] = memo.trip(p);
          EXPECT_GE(fresh_substation_J(models, moved, t), fresh - 1.0)
              << "train " << k << " dwell " << j << " section " << i << " sign " << sign;
          ++checked;
        }
      }
    }
  }
  EXPECT_GT(checked, 0);
}

}  // namespace
}  // namespace ecorail::fleet
