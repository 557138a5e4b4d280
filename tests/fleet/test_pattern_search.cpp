// Pattern optimisation on the small fleet: the result is never worse than the headways alone,
// every dwell stays in its range and the trip keeps its time, and the pattern found is a local
// optimum: no single move of one second (a dwell against a neighbouring section, or between
// neighbouring sections), checked here by its own re-solves, lowers the substation energy at the
// departures the search fixed.
#include <gtest/gtest.h>

#include <numeric>

#include "energy/fleet_energy_model.hpp"
#include "fleet/pattern_search.hpp"
#include "fleet_fixture.hpp"

namespace ecorail::fleet {
namespace {

TEST(PatternSearch, NeverWorseFeasibleAndLocallyOptimal) {
  FleetProblem problem = testing::small_fleet(6, 150, 250, 1000);
  problem.trip_time_s = 480.0;  // the small pattern's trip
  EnergyModelOptions model;
  model.time_step_s = 0.1;
  PatternSearchOptions o;
  o.headways.moves_per_run = 3000;
  o.deltas_s = {2.0, 1.0};
  const auto& lib = testing::small_library();
  const PatternSearchResult r = optimise_pattern(lib, problem, model, testing::small_pattern(), o);
  const FleetEnergy& after = r.timetable.evaluation.total;
  EXPECT_LE(after.substation_J(), r.headways_only.total.substation_J() + 1e-6);
  for (double d : r.pattern.pattern.dwells_s) {
    EXPECT_GE(d, problem.dwell_min_s);
    EXPECT_LE(d, problem.dwell_max_s);
  }
  EXPECT_NEAR(r.pattern.pattern.trip_time_s(), problem.trip_time_s, 0.05);
  EXPECT_NEAR(r.pattern.trip.stops().back().arrival_s, problem.trip_time_s, 0.05);

  // Local optimality at the departures of the pattern phase (the headways-only optimum).
  const std::vector<int>& t = r.headways_only.departures_s;
  const double found = TestFleet(r.pattern.trip, problem, model).evaluate(t).total.substation_J();
  const FleetPattern& best = r.pattern.pattern;
  const std::size_t n = lib.size();
  int checked = 0;
  for (std::size_t j = 0; j + 1 < n; ++j) {
    for (std::size_t i : {j, j + 1}) {
      for (double sign : {+1.0, -1.0}) {
        FleetPattern p = best;
        p.dwells_s[j] += sign;
        p.running_times_s[i] -= sign;
        if (p.dwells_s[j] < problem.dwell_min_s || p.dwells_s[j] > problem.dwell_max_s) continue;
        const PatternTrip trip = pattern_trip(lib, p);
        const double e = TestFleet(trip.trip, problem, model).evaluate(t).total.substation_J();
        EXPECT_GE(e, found - 1.0) << "dwell " << j << " section " << i << " sign " << sign;
        ++checked;
      }
    }
  }
  EXPECT_GT(checked, 0);
}

}  // namespace
}  // namespace ecorail::fleet
