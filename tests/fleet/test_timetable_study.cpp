// TimetableStudy::with_problem: the study of another fleet problem shares the section library
// (nothing is solved again) and gives the same evaluation, to the last digit, as a study built
// from scratch for that problem; and optimise() returns a flagged summary instead of throwing.
#include <gtest/gtest.h>

#include "data/line_loader.hpp"
#include "data/route_builder.hpp"
#include "data/train_io.hpp"
#include "fleet/timetable_study.hpp"
#include "fleet_fixture.hpp"

namespace ecorail::fleet {
namespace {

TimetableStudySetup small_setup(const FleetProblem& problem) {
  TimetableStudySetup s;
  s.line = data::default_line();
  s.train = data::default_train();
  s.stops = data::stops_between(s.line, "A6", "A9");
  s.dwell_s = 30.0;
  s.problem = problem;
  s.problem.trip_time_s = 480.0;
  s.problem.dwell_min_s = 30.0;
  s.problem.dwell_max_s = 45.0;
  s.model.model = "power-flow";
  s.model.time_step_s = 0.1;
  return s;
}

TEST(TimetableStudy, WithProblemSharesTheSectionsAndEqualsAFreshStudy) {
  const TimetableStudySetup first = small_setup(testing::small_fleet(4, 60, 200, 480));
  const TimetableStudy study(first);
  FleetProblem other = first.problem;
  other.trains = 6;
  other.span_s = 700;
  const std::unique_ptr<TimetableStudy> derived = study.with_problem(other);
  EXPECT_EQ(&derived->library(), &study.library());  // the sections are not solved again
  EXPECT_EQ(derived->problem().trains, 6);
  TimetableStudySetup fresh_setup = first;
  fresh_setup.problem = other;
  const TimetableStudy fresh(fresh_setup);
  const std::vector<int> departures = {0, 130, 260, 390, 560, 700};
  const FleetEvaluation a = derived->evaluate(departures).evaluation;
  const FleetEvaluation b = fresh.evaluate(departures).evaluation;
  EXPECT_EQ(a.total.traction_J, b.total.traction_J);
  EXPECT_EQ(a.total.used_regen_J, b.total.used_regen_J);
  EXPECT_EQ(a.total.substation_J(), b.total.substation_J());
  EXPECT_GT(a.total.used_regen_J, 0.0);  // the trains do share regenerated energy
  // A problem that is not valid is refused, as by the constructor.
  FleetProblem bad = other;
  bad.trains = 0;
  EXPECT_THROW(study.with_problem(bad), std::invalid_argument);
}

TEST(TimetableStudy, OptimiseReturnsItsSummaryWithoutThrowing) {
  TimetableStudy study(small_setup(testing::small_fleet(4, 60, 200, 480)));
  StudyOptimiseOptions o;
  o.headways.moves_per_run = 2000;
  o.headways.restarts = 1;
  o.headways.gap_fraction = 0.5;
  const StudyOptimisation r = study.optimise(o);
  EXPECT_TRUE(r.result.summary.IsSolutionUsable());
  const std::vector<int>& t = r.result.evaluation.departures_s;
  ASSERT_EQ(t.size(), 4u);
  EXPECT_EQ(t.front(), 0);
  EXPECT_EQ(t.back(), 480);
  // Its figure is the model's own evaluation of the departures it returns.
  EXPECT_DOUBLE_EQ(r.result.evaluation.total.substation_J(),
                   study.evaluate(t).evaluation.total.substation_J());
}

}  // namespace
}  // namespace ecorail::fleet
