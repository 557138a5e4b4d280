// Every options struct of dp/ checks itself before any work: the defaults are valid, and one bad
// value per field gives a message that names the field. The solvers refuse invalid options with
// std::invalid_argument before building anything.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "data/line_loader.hpp"
#include "data/route_builder.hpp"
#include "data/train_io.hpp"
#include "dp/frontier.hpp"
#include "dp/journey.hpp"
#include "dp/section_solve.hpp"

namespace ecorail::dp {
namespace {

template <typename Options>
struct Case {
  const char* field;
  std::function<void(Options&)> spoil;
};

// The defaults pass; each spoiled copy fails with a message naming its field.
template <typename Options>
void expect_each_named(const std::vector<Case<Options>>& cases) {
  std::string why;
  EXPECT_TRUE(Options{}.IsValid(&why)) << why;
  for (const auto& c : cases) {
    Options o;
    c.spoil(o);
    why.clear();
    EXPECT_FALSE(o.IsValid(&why)) << c.field;
    EXPECT_NE(why.find(c.field), std::string::npos) << c.field << ": " << why;
    EXPECT_FALSE(o.IsValid(nullptr)) << c.field;  // no message asked for: still refused
  }
}

TEST(Options, EngineOptionsNameTheBadField) {
  expect_each_named<EngineOptions>({
      {"ds_m", [](EngineOptions& o) { o.grid.ds_m = -5.0; }},
      {"dv_kmh", [](EngineOptions& o) { o.grid.dv_kmh = 0.0; }},
      {"substep_m", [](EngineOptions& o) { o.grid.substep_m = 0.0; }},
      {"objective", [](EngineOptions& o) { o.objective = static_cast<Objective>(7); }},
      {"resim_step_m", [](EngineOptions& o) { o.resim_step_m = 2.0; }},
      {"envelope_resolution_m", [](EngineOptions& o) { o.envelope_resolution_m = NAN; }},
      {"decision_step_m", [](EngineOptions& o) { o.decision_step_m = 0.0; }},
      {"threads", [](EngineOptions& o) { o.threads = -1; }},
  });
}

TEST(Options, TimeSearchOptionsNameTheBadField) {
  expect_each_named<TimeSearchOptions>({
      {"tolerance_s", [](TimeSearchOptions& o) { o.tolerance_s = 0.0; }},
      {"lambda_tolerance_s", [](TimeSearchOptions& o) { o.lambda_tolerance_s = 1e-4; }},
      {"max_iterations", [](TimeSearchOptions& o) { o.max_iterations = 0; }},
      {"lambda_guess", [](TimeSearchOptions& o) { o.lambda_guess = -1.0; }},
      {"bracket_factor", [](TimeSearchOptions& o) { o.bracket_factor = 1.0; }},
  });
}

TEST(Options, SectionSolveOptionsNameTheBadField) {
  expect_each_named<SectionSolveOptions>({
      {"ds_m", [](SectionSolveOptions& o) { o.engine.grid.ds_m = 1000.0; }},
      {"max_iterations", [](SectionSolveOptions& o) { o.search.max_iterations = -3; }},
  });
}

TEST(Options, JourneyOptionsNameTheBadField) {
  expect_each_named<JourneyOptions>({
      {"dv_kmh", [](JourneyOptions& o) { o.engine.grid.dv_kmh = 50.0; }},
      {"tolerance_s", [](JourneyOptions& o) { o.search.tolerance_s = 1.0; }},
      {"split", [](JourneyOptions& o) { o.split = static_cast<Split>(9); }},
      {"marginal_step_s", [](JourneyOptions& o) { o.marginal_step_s = 0.0; }},
      {"position_m", [](JourneyOptions& o) { o.start.position_m = -1.0; }},
      {"speed_ms", [](JourneyOptions& o) { o.start.speed_ms = INFINITY; }},
  });
}

TEST(Options, FrontierOptionsNameTheBadField) {
  expect_each_named<FrontierOptions>({
      {"t_min_s", [](FrontierOptions& o) { o.t_min_s = -1.0; }},
      {"t_max_s", [](FrontierOptions& o) { o.t_max_s = NAN; }},
      {"t_max_s", [](FrontierOptions& o) { o.t_min_s = 120.0, o.t_max_s = 100.0; }},
      {"step_s", [](FrontierOptions& o) { o.step_s = 0.0; }},
      {"convexity_tolerance", [](FrontierOptions& o) { o.convexity_tolerance = -1e-5; }},
      {"bracket_factor", [](FrontierOptions& o) { o.search.bracket_factor = 0.5; }},
  });
}

TEST(Options, SectionLibraryOptionsIncludeEngineAndSearchChecks) {
  expect_each_named<SectionLibraryOptions>({
      {"threads", [](SectionLibraryOptions& o) { o.engine.threads = -2; }},
      {"lambda_guess", [](SectionLibraryOptions& o) { o.search.lambda_guess = 0.0; }},
  });
}

// Invalid options are refused before any work: the message is the IsValid one.
TEST(Options, SolversRefuseInvalidOptionsBeforeAnyWork) {
  const data::Line line = data::default_line();
  const physics::Train train = data::default_train();
  const physics::Route route = data::build_route(line, "A6", "A7", train);

  SectionSolveOptions section;
  section.engine.grid.ds_m = 0.0;
  try {
    solve_section(train, route, 110.0, section);
    ADD_FAILURE() << "solve_section accepted ds_m = 0";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("ds_m"), std::string::npos) << e.what();
  }

  EngineOptions engine;
  engine.threads = -1;
  EXPECT_THROW(SectionEngine(train, route, engine), std::invalid_argument);

  JourneyOptions journey;
  journey.marginal_step_s = -1.0;
  try {
    solve_journey(train, {route}, {}, 110.0, journey);
    ADD_FAILURE() << "solve_journey accepted marginal_step_s = -1";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("marginal_step_s"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace ecorail::dp
