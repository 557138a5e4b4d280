// Restarts, journeys on a section library and free dwells. A restart of the optimal run at a
// point of its own trajectory, with the time it has left, must find the energy it has left
// (Bellman's principle, checked through independent re-solves); a restart that cannot make its
// time says what the minimum is; a journey on a built library builds nothing more; free dwells
// go to their minimum and no other feasible dwell choice is cheaper.
#include <gtest/gtest.h>

#include <cmath>

#include "data/line_loader.hpp"
#include "data/route_builder.hpp"
#include "data/train_io.hpp"
#include "dp/journey.hpp"
#include "dp/section_library.hpp"

namespace ecorail::dp {
namespace {

std::vector<physics::Route> routes(const physics::Train& train,
                                   const std::vector<std::string>& stops) {
  return data::build_routes(data::default_line(), stops, train);
}

// The energy and time of a run from the first trace point at or after position s onwards.
struct Rest {
  StartState start;
  double time_s = 0.0, energy_J = 0.0;
};
Rest rest_of(const SectionEngine& engine, const physics::SimulationResult& sim, double s) {
  Rest r;
  const physics::Train& train = engine.train();
  double traction = 0.0, brake = 0.0;
  bool in = false;
  for (std::size_t k = 1; k < sim.trace.size(); ++k) {
    const auto& a = sim.trace[k - 1];
    const auto& b = sim.trace[k];
    if (!in && a.s_m >= s) {
      in = true;
      r.start = {a.s_m, a.v_ms};
      r.time_s = sim.running_time_s - a.t_s;
    }
    if (!in) continue;
    const double work = b.force_N * (b.s_m - a.s_m);
    (work > 0.0 ? traction : brake) += std::abs(work);
  }
  r.energy_J = energy_cost_J(engine.options().objective, train, traction, brake);
  return r;
}

TEST(Restart, FromItsOwnTrajectoryReproducesTheRemainingEnergy) {
  const physics::Train train = data::default_train();
  const SectionLibrary library(train, routes(train, {"A6", "A7"}), {});
  const SectionEngine& engine = library.engine(0);
  const SectionTimeSolve whole = library.solve(0, 110.0);
  ASSERT_TRUE(whole.search.converged);
  for (double s : {100.0, 400.0, 900.0, 1250.0}) {
    const Rest rest = rest_of(engine, whole.search.run.sim, s);
    ASSERT_GT(rest.start.speed_ms, 1.0) << s;
    const TimeSearchResult again =
        solve_for_time(engine, rest.time_s, library.options().search, rest.start);
    ASSERT_TRUE(again.converged) << s;
    EXPECT_NEAR(again.run.sim.running_time_s, rest.time_s, 0.01) << s;
    EXPECT_LT(std::abs(again.run.sim.stop_error_m), 0.05) << s;
    EXPECT_NEAR(engine.energy_cost_J(again.run.sim), rest.energy_J, 5e-4 * rest.energy_J)
        << "restart at " << s << " m";
  }
}

TEST(Restart, ThatCannotMakeItsTimeStatesTheMinimum) {
  const physics::Train train = data::default_train();
  const SectionLibrary library(train, routes(train, {"A6", "A7"}), {});
  const StartState start{600.0, 10.0};
  const double t_min = library.engine(0).min_time_run(start).running_time_s;
  try {
    solve_for_time(library.engine(0), t_min - 5.0, library.options().search, start);
    FAIL() << "expected InfeasibleTimeError";
  } catch (const InfeasibleTimeError& e) {
    EXPECT_NEAR(e.minimum_s(), t_min, 1e-9);
    EXPECT_NE(std::string(e.what()).find("minimum"), std::string::npos);
  }
  // Slower than the flat-out rest but feasible: solved to the time.
  const TimeSearchResult ok =
      solve_for_time(library.engine(0), t_min + 10.0, library.options().search, start);
  EXPECT_NEAR(ok.run.sim.running_time_s, t_min + 10.0, 0.01);
}

TEST(Restart, JourneyRestartMatchesTheRestOfTheJourney) {
  const physics::Train train = data::default_train();
  const SectionLibrary library(train, routes(train, {"A6", "A7", "A8"}), {});
  JourneyOptions options;
  options.measure_marginals = false;
  const JourneySolution whole = solve_journey(library, 0, 2, {45.0}, 220.0, options);
  ASSERT_TRUE(whole.converged());
  const Rest rest = rest_of(library.engine(0), whole.sections[0].run.sim, 500.0);
  JourneyOptions restart = options;
  restart.start = rest.start;
  const double remaining = rest.time_s + whole.sections[1].run.sim.running_time_s;
  const JourneySolution again = solve_journey(library, 0, 2, {45.0}, remaining, restart);
  ASSERT_TRUE(again.converged());
  const double expected =
      rest.energy_J + library.engine(1).energy_cost_J(whole.sections[1].run.sim);
  const double got = library.engine(0).energy_cost_J(again.sections[0].run.sim) +
                     library.engine(1).energy_cost_J(again.sections[1].run.sim);
  EXPECT_NEAR(got, expected, 5e-4 * expected);
}

TEST(JourneyOnLibrary, SecondJourneyBuildsNothingAndMatchesTheOneShotSolve) {
  const physics::Train train = data::default_train();
  const auto r = routes(train, {"A6", "A7", "A8"});
  const SectionLibrary library(train, r, {});
  JourneyOptions options;
  options.measure_marginals = false;
  const JourneySolution first = solve_journey(library, 0, 2, {45.0}, 220.0, options);
  EXPECT_EQ(library.engine_builds(), 2);
  const JourneySolution second = solve_journey(library, 0, 2, {30.0}, 230.0, options);
  EXPECT_EQ(library.engine_builds(), 2);
  EXPECT_LT(second.traction_work_J, first.traction_work_J);
  const JourneySolution one_shot = solve_journey(train, r, {45.0}, 220.0, options);
  EXPECT_DOUBLE_EQ(one_shot.traction_work_J, first.traction_work_J);
}

// With every frontier in the library the price search starts where the frontiers put it: fewer
// evaluations, the same optimum to a second-order trim (1e-5 of the energy).
TEST(JourneyOnLibrary, FrontiersStartThePriceSearchAndChangeNothingButItsCost) {
  const physics::Train train = data::default_train();
  SectionLibraryOptions lo;
  lo.frontier_span_s = 40.0;
  const SectionLibrary library(train, routes(train, {"A6", "A7", "A8", "A9"}), lo);
  JourneyOptions options;
  options.measure_marginals = false;
  const JourneySolution cold = solve_journey(library, 0, 3, {30.0, 30.0}, 340.0, options);
  library.build_frontiers(0, 3, nullptr);
  const JourneySolution warm = solve_journey(library, 0, 3, {30.0, 30.0}, 340.0, options);
  ASSERT_TRUE(cold.converged());
  ASSERT_TRUE(warm.converged());
  EXPECT_NEAR(warm.running_time_s, 340.0, 0.01);
  EXPECT_LT(warm.lambda_evaluations, cold.lambda_evaluations);
  EXPECT_NEAR(warm.traction_work_J, cold.traction_work_J, 1e-5 * cold.traction_work_J);
}

TEST(FreeDwells, GoToTheirMinimumAndNoOtherChoiceIsCheaper) {
  const physics::Train train = data::default_train();
  const SectionLibrary library(train, routes(train, {"A6", "A7", "A8", "A9"}), {});
  JourneyOptions options;
  options.measure_marginals = false;
  const std::vector<DwellRange> ranges{{30.0, 45.0}, {30.0, 45.0}};
  const double trip = 400.0;
  const JourneySolution free = solve_journey_free_dwells(library, 0, 3, ranges, trip, options);
  ASSERT_TRUE(free.converged());
  EXPECT_DOUBLE_EQ(free.sections[0].dwell_after_s, 30.0);
  EXPECT_DOUBLE_EQ(free.sections[1].dwell_after_s, 30.0);
  EXPECT_NEAR(free.running_time_s + 60.0, trip, 0.01);
  const double e_free = free.traction_work_J;
  // Brute force over a grid of dwell choices in the ranges: none is cheaper.
  for (double d1 : {30.0, 37.0, 45.0}) {
    for (double d2 : {30.0, 45.0}) {
      if (d1 == 30.0 && d2 == 30.0) continue;
      const JourneySolution other = solve_journey(library, 0, 3, {d1, d2}, trip - d1 - d2, options);
      EXPECT_GT(other.traction_work_J, e_free) << d1 << " " << d2;
    }
  }
  EXPECT_THROW(solve_journey_free_dwells(library, 0, 3, ranges, 200.0, options),
               InfeasibleTimeError);
  EXPECT_THROW(
      solve_journey_free_dwells(library, 0, 3, {{45.0, 30.0}, {30.0, 45.0}}, trip, options),
      std::invalid_argument);
}

}  // namespace
}  // namespace ecorail::dp
