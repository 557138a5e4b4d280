// Every solver reports the same way (dp/termination.hpp): a section solve, a journey and a
// frontier each return a summary with a Termination, IsSolutionUsable(), BriefReport() and
// FullReport(). A solve that meets its targets is CONVERGENCE and usable; one whose search is cut
// short is NO_CONVERGENCE and not usable; one without a run that arrives is FAILURE. Names go to
// and from text in one place.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "data/line_loader.hpp"
#include "data/route_builder.hpp"
#include "data/train_io.hpp"
#include "dp/frontier.hpp"
#include "dp/journey.hpp"
#include "dp/journey_plan.hpp"
#include "dp/section_solve.hpp"
#include "dp/termination.hpp"

namespace ecorail::dp {
namespace {

bool ends_with(const std::string& text, const std::string& tail) {
  return text.size() >= tail.size() &&
         text.compare(text.size() - tail.size(), tail.size(), tail) == 0;
}

TEST(Termination, NamesRoundTripAndOnlyConvergenceIsUsable) {
  for (Termination t :
       {Termination::CONVERGENCE, Termination::NO_CONVERGENCE, Termination::FAILURE}) {
    EXPECT_EQ(termination_from_name(termination_name(t)), t);
  }
  EXPECT_FALSE(termination_from_name("converged").has_value());
  EXPECT_TRUE(is_usable(Termination::CONVERGENCE));
  EXPECT_FALSE(is_usable(Termination::NO_CONVERGENCE));
  EXPECT_FALSE(is_usable(Termination::FAILURE));
  EXPECT_EQ(termination_of(true, true), Termination::CONVERGENCE);
  EXPECT_EQ(termination_of(true, false), Termination::NO_CONVERGENCE);
  EXPECT_EQ(termination_of(false, true), Termination::FAILURE);  // a missed stop is never usable
  EXPECT_EQ(status_word(Termination::CONVERGENCE, 1), "WARNINGS");
  EXPECT_EQ(status_word(Termination::NO_CONVERGENCE, 0), "NO_CONVERGENCE");
}

struct Problem {
  data::Line line = data::default_line();
  physics::Train train = data::default_train();
  physics::Route route = data::build_route(line, "A6", "A7", train);
};

TEST(Termination, SectionSolveUsableAndCutShort) {
  const Problem p;
  const SectionSolution good = solve_section(p.train, p.route, 110.0, {});
  EXPECT_EQ(good.summary.termination, Termination::CONVERGENCE);
  EXPECT_TRUE(good.summary.IsSolutionUsable());
  EXPECT_TRUE(good.summary.converged());
  EXPECT_TRUE(ends_with(good.summary.BriefReport(), "CONVERGENCE\n"));
  EXPECT_NE(good.summary.FullReport().find("Termination                  CONVERGENCE"),
            std::string::npos);

  // Two lambda evaluations and no trim cannot close a 1 ms tolerance: the run arrives (it is a
  // DP run) but misses its time.
  SectionSolveOptions short_search;
  short_search.search.max_iterations = 2;
  short_search.search.trim = false;
  const SectionSolution cut = solve_section(p.train, p.route, 110.0, short_search);
  EXPECT_EQ(cut.summary.termination, Termination::NO_CONVERGENCE);
  EXPECT_FALSE(cut.summary.IsSolutionUsable());
  EXPECT_FALSE(cut.summary.converged());
  EXPECT_GT(std::abs(cut.summary.running_time_s - 110.0), 0.1);
  EXPECT_TRUE(ends_with(cut.summary.BriefReport(), "NO_CONVERGENCE\n"));
  EXPECT_NE(cut.summary.FullReport().find("NO_CONVERGENCE"), std::string::npos);
}

TEST(Termination, JourneySummaryUsesTheSectionNamesAndUnits) {
  const Problem p;
  const std::vector<physics::Route> routes = {p.route,
                                              data::build_route(p.line, "A7", "A8", p.train)};
  JourneyOptions options;
  options.measure_marginals = false;
  const JourneySolution sol = solve_journey(p.train, routes, {45.0}, 220.0, options);
  const JourneySummary& s = sol.summary;
  EXPECT_EQ(s.termination, Termination::CONVERGENCE);
  EXPECT_TRUE(s.IsSolutionUsable());
  EXPECT_EQ(s.from, "A6");
  EXPECT_EQ(s.to, "A8");
  EXPECT_EQ(s.sections, 2);
  // kJ at the edge, J inside: the summary and the solution agree.
  EXPECT_DOUBLE_EQ(s.traction_energy_kJ, sol.traction_work_J / 1000.0);
  EXPECT_DOUBLE_EQ(s.running_time_s, sol.running_time_s);
  EXPECT_DOUBLE_EQ(s.dwell_time_s, 45.0);
  EXPECT_NEAR(s.distance_m, routes[0].length_m() + routes[1].length_m(), 1e-9);
  EXPECT_LT(std::abs(s.stop_error_m), kStopTolerance_m);
  EXPECT_TRUE(ends_with(s.BriefReport(), "CONVERGENCE\n"));

  // The same journey laid out as a trip: arrival = departure + running time + dwell.
  const physics::Trip trip = journey_trip(sol, routes, 3600.0, p.train.regen_efficiency);
  EXPECT_NEAR(trip.arrival_s(), 3600.0 + sol.running_time_s + 45.0, 1e-9);
  EXPECT_NEAR(trip.ledger().traction_work_J, sol.traction_work_J, 1e-6 * sol.traction_work_J);

  // Cut short, with no trim: not usable.
  options.search.max_iterations = 1;
  options.search.trim = false;
  options.use_frontiers = false;
  const JourneySolution cut = solve_journey(p.train, routes, {45.0}, 220.0, options);
  EXPECT_EQ(cut.summary.termination, Termination::NO_CONVERGENCE);
  EXPECT_FALSE(cut.summary.IsSolutionUsable());
  EXPECT_FALSE(cut.converged());
}

TEST(Termination, FrontierSummaryCountsPointsThatMissTheirTime) {
  const Problem p;
  const SectionEngine engine(p.train, p.route, {});
  FrontierOptions options;
  options.t_max_s = engine.min_time_run().running_time_s + 6.0;
  options.step_s = 2.0;
  Frontier f = compute_frontier(engine, options);
  FrontierSummary s = summarize_frontier(f, "A6", "A7");
  EXPECT_EQ(s.termination, Termination::CONVERGENCE);
  EXPECT_TRUE(s.IsSolutionUsable());
  EXPECT_EQ(s.points, static_cast<int>(f.points.size()));
  EXPECT_EQ(s.converged_points, s.points);
  EXPECT_NE(s.BriefReport().find("A6 -> A7"), std::string::npos);

  f.points[1].converged = false;
  s = summarize_frontier(f, "A6", "A7");
  EXPECT_EQ(s.termination, Termination::NO_CONVERGENCE);
  EXPECT_FALSE(s.IsSolutionUsable());
  EXPECT_NE(s.FullReport().find("missed their running time"), std::string::npos);

  f.points.clear();
  EXPECT_EQ(summarize_frontier(f, "A6", "A7").termination, Termination::FAILURE);
}

TEST(JourneyPlan, DwellsByNameWithAFallbackAndClearErrors) {
  const std::vector<std::string> stops = {"A6", "A7", "A8", "A9"};
  DwellSpec spec;
  spec.by_stop_s = {{"A8", 45.0}};
  spec.every_stop_s = 30.0;
  EXPECT_EQ(resolve_dwells(spec, stops), (std::vector<double>{30.0, 45.0}));

  spec.every_stop_s.reset();
  try {
    resolve_dwells(spec, stops);
    ADD_FAILURE() << "A7 has no dwell";
  } catch (const DwellError& e) {
    EXPECT_NE(std::string(e.what()).find("A7"), std::string::npos) << e.what();
  }
  spec.by_stop_s = {{"A9", 45.0}};  // the last stop is no intermediate stop
  spec.every_stop_s = 30.0;
  EXPECT_THROW(resolve_dwells(spec, stops), DwellError);
  spec.by_stop_s = {{"A7", -1.0}};
  EXPECT_THROW(resolve_dwells(spec, stops), DwellError);
}

}  // namespace
}  // namespace ecorail::dp
