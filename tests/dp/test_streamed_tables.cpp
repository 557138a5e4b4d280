// A line whose transition tables do not fit in memory together streams them
// (SectionLibraryOptions::memory_budget_bytes): each engine builds its table for each sweep and
// frees it. The journey must come out bit for bit as with the tables kept, and no streaming
// engine may hold a table after the solve.
#include <gtest/gtest.h>

#include "data/line_loader.hpp"
#include "data/route_builder.hpp"
#include "data/train_io.hpp"
#include "dp/journey.hpp"
#include "dp/section_library.hpp"
#include "tests/dp/coarse_library.hpp"

namespace ecorail {
namespace {

dp::SectionLibraryOptions coarse(double budget_bytes) {
  return dp::test::coarse_library(10.0, budget_bytes);
}

TEST(StreamedTables, AJourneyIsBitForBitTheSameAndNoTableIsKept) {
  const data::Line line = data::default_line();
  const physics::Train train = data::default_train();
  const std::vector<physics::Route> routes =
      data::build_routes(line, data::stops_between(line, "A6", "A9"), train);
  const dp::SectionLibrary kept(train, routes, coarse(0.0));
  const dp::SectionLibrary streamed(train, routes, coarse(1.0));  // nothing fits: stream
  EXPECT_FALSE(kept.streams_tables());
  EXPECT_TRUE(streamed.streams_tables());
  EXPECT_GT(streamed.tables_estimate_bytes(), 1.0);
  EXPECT_EQ(kept.tables_estimate_bytes(), streamed.tables_estimate_bytes());

  dp::JourneyOptions options;
  options.engine = coarse(0.0).engine;
  const std::vector<double> dwells{30.0, 30.0};
  const dp::JourneySolution a = dp::solve_journey(kept, 0, 3, dwells, 330.0, options);
  const dp::JourneySolution b = dp::solve_journey(streamed, 0, 3, dwells, 330.0, options);
  ASSERT_TRUE(a.summary.IsSolutionUsable());
  ASSERT_TRUE(b.summary.IsSolutionUsable());
  EXPECT_FALSE(a.summary.streamed_tables);
  EXPECT_TRUE(b.summary.streamed_tables);
  EXPECT_EQ(a.traction_work_J, b.traction_work_J);
  EXPECT_EQ(a.lambda_J_per_s, b.lambda_J_per_s);
  ASSERT_EQ(a.sections.size(), b.sections.size());
  for (std::size_t i = 0; i < a.sections.size(); ++i) {
    EXPECT_EQ(a.sections[i].run.sim.running_time_s, b.sections[i].run.sim.running_time_s);
    EXPECT_EQ(a.sections[i].run.program.size(), b.sections[i].run.program.size());
    EXPECT_TRUE(kept.engine(i).holds_transitions());
    EXPECT_FALSE(streamed.engine(i).holds_transitions());
  }
  // A single section never streams: its one table is needed whole anyway.
  const dp::SectionLibrary one(train, {routes[0]}, coarse(1.0));
  EXPECT_FALSE(one.streams_tables());
  std::string why;
  dp::SectionLibraryOptions bad = coarse(-1.0);
  EXPECT_FALSE(bad.IsValid(&why));
  EXPECT_NE(why.find("memory_budget_bytes"), std::string::npos);
}

}  // namespace
}  // namespace ecorail
