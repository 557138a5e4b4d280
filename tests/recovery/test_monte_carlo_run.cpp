// What a Monte Carlo run reports besides its days: the summary's termination (CONVERGENCE only
// when every day asked for is there with finite statistics), punctuality per station as the
// counts say, the recovery policies' names both ways, and the plan's timetable CSV read back
// to the same plan (one layout for writer and reader).
#include <gtest/gtest.h>

#include <unistd.h>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "output/timetable_csv_writer.hpp"
#include "recovery/monte_carlo_run.hpp"
#include "recovery/plan_source.hpp"

namespace ecorail::recovery {
namespace {

MonteCarloRun three_days() {
  MonteCarloRun run;
  run.stations = {"A", "B", "C"};
  for (std::uint64_t d = 0; d < 3; ++d) {
    DayRecord r;
    r.day = d;
    r.arrivals = 4;
    r.punctual = static_cast<std::int64_t>(2 + d % 2);
    r.station_arrivals = {0, 2, 2};
    r.station_punctual = {0, 2, r.punctual - 2};
    r.traction_kJ = 100.0 + static_cast<double>(d);
    r.substation_kJ = 80.0;
    r.lateness_histogram.assign(kLatenessHistogramBins, 0);
    r.lateness_histogram[0] = 4;
    run.days.push_back(r);
  }
  run.histogram = pooled_histogram(run.days);
  run.plan_energy = {{"traction_kJ", 90.0}, {"substation_kJ", 70.0}};
  return run;
}

TEST(MonteCarloRun, SummaryConvergesOnlyOnEveryDayWithFiniteStatistics) {
  MonteCarloRun run = three_days();
  const MonteCarloSummary ok = run_summary(run);
  EXPECT_EQ(ok.termination, dp::Termination::CONVERGENCE);
  EXPECT_EQ(ok.last_day, 3u);
  EXPECT_DOUBLE_EQ(ok.statistics.traction_kJ.mean, 101.0);
  EXPECT_DOUBLE_EQ(ok.plan_substation_kJ, 70.0);
  run.days[1].traction_kJ = std::nan("");
  EXPECT_EQ(run_summary(run).termination, dp::Termination::FAILURE);
  EXPECT_FALSE(run_summary(run).IsSolutionUsable());
}

TEST(MonteCarloRun, StationPunctualityFollowsTheCounts) {
  const MonteCarloRun run = three_days();
  const std::vector<StationPunctuality> p =
      station_punctuality(summarise(run.days, run.histogram), run.stations);
  ASSERT_EQ(p.size(), 2u);  // the first station has no arrivals to count
  EXPECT_EQ(p[0].station, "B");
  EXPECT_EQ(p[0].arrivals, 6);
  EXPECT_DOUBLE_EQ(p[0].punctuality, 1.0);
  EXPECT_EQ(p[1].station, "C");
  EXPECT_EQ(p[1].punctual, 0 + 1 + 0);
  EXPECT_DOUBLE_EQ(p[1].punctuality, 1.0 / 6.0);
}

TEST(MonteCarloRun, PolicyNamesRoundTrip) {
  for (RecoveryPolicy p :
       {RecoveryPolicy::Exact, RecoveryPolicy::ExactPunctual, RecoveryPolicy::Rule}) {
    const auto back = recovery_policy_from_name(recovery_policy_name(p));
    ASSERT_TRUE(back.has_value());
    EXPECT_EQ(*back, p);
  }
  EXPECT_FALSE(recovery_policy_from_name("fast").has_value());
}

TEST(PlanCsv, WrittenPlanReadsBackToTheSamePlan) {
  const Plan plan = plan_from_pattern({"A6", "A7", "A8"}, {95.25, 110.5}, {30.0}, {0.0, 150.0});
  const std::filesystem::path file = std::filesystem::temp_directory_path() /
                                     ("ecorail-plan-" + std::to_string(getpid()) + ".csv");
  {
    std::ofstream out(file);
    output::write_timetable_csv(out, plan, {0.0, 1200.0, 2300.0});
  }
  const Plan back = read_plan_csv(file.string());
  std::filesystem::remove(file);
  ASSERT_EQ(back.stations, plan.stations);
  ASSERT_EQ(back.trains.size(), plan.trains.size());
  for (std::size_t k = 0; k < plan.trains.size(); ++k)
    for (std::size_t j = 0; j < plan.stations.size(); ++j) {
      EXPECT_NEAR(back.trains[k].arrival_s[j], plan.trains[k].arrival_s[j], 5e-4);
      EXPECT_NEAR(back.trains[k].departure_s[j], plan.trains[k].departure_s[j], 5e-4);
    }
}

}  // namespace
}  // namespace ecorail::recovery
