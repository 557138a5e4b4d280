// Policy ladders (policy/ladder.hpp): the options check themselves, naming the field; a ladder
// builds one layer per offset at the running time it asks for; a rung below the flat-out run is
// a LadderTimeError that says which offset it was. Coarse grid (ds 50 m, dv 4 km/h) on A6 -> A7.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "data/line_loader.hpp"
#include "data/route_builder.hpp"
#include "data/train_io.hpp"
#include "policy/ladder.hpp"

namespace ecorail::policy {
namespace {

TEST(PolicyLadderOptions, EachBadValueIsNamed) {
  struct Case {
    const char* field;
    void (*spoil)(PolicyLadderOptions&);
  };
  const Case cases[] = {
      {"nominal_time_s", [](PolicyLadderOptions& o) { o.nominal_time_s = 0.0; }},
      {"time_offsets_s", [](PolicyLadderOptions& o) { o.time_offsets_s.clear(); }},
      {"time_offsets_s",
       [](PolicyLadderOptions& o) {
         o.time_offsets_s = {0.0, 5.0, 0.0};
       }},
      {"time_offsets_s", [](PolicyLadderOptions& o) { o.time_offsets_s = {-200.0}; }},
      {"max_iterations", [](PolicyLadderOptions& o) { o.search.max_iterations = 0; }},
  };
  PolicyLadderOptions good;
  good.nominal_time_s = 110.0;
  std::string why;
  EXPECT_TRUE(good.IsValid(&why)) << why;
  for (const Case& c : cases) {
    PolicyLadderOptions o = good;
    c.spoil(o);
    EXPECT_FALSE(o.IsValid(&why)) << c.field;
    EXPECT_NE(why.find(c.field), std::string::npos) << why;
  }
}

struct Section {
  data::Line line = data::default_line();
  physics::Train train = data::default_train();
  physics::Route route = data::build_route(line, "A6", "A7", train);
  dp::EngineOptions coarse() const {
    dp::EngineOptions o;
    o.grid = {50.0, 4.0, 25.0};
    return o;
  }
};

TEST(PolicyLadder, OneLayerPerOffsetAtItsRunningTime) {
  const Section s;
  const dp::SectionEngine engine(s.train, s.route, s.coarse());
  PolicyLadderOptions options;
  options.nominal_time_s = 110.0;
  options.time_offsets_s = {-5.0, 0.0, 5.0};
  const PolicyTable table = build_policy_ladder(
      engine, {s.line.name, s.line.checksum(), data::train_checksum(s.train)}, options);
  ASSERT_EQ(table.layers.size(), 3u);
  EXPECT_EQ(table.nominal_layer(), 1);
  for (std::size_t k = 0; k < 3; ++k) {
    const PolicyLayer& L = table.layers[k];
    EXPECT_DOUBLE_EQ(L.time_offset_s, options.time_offsets_s[k]);
    EXPECT_DOUBLE_EQ(L.target_time_s, 110.0 + options.time_offsets_s[k]);
    // The layer's own re-simulated run lies close to its target (the DP run before any trim).
    EXPECT_NEAR(L.planned_time_s, L.target_time_s, 1.0) << k;
  }
  // A faster layer pays a higher time price.
  EXPECT_GT(table.layers[0].lambda_J_per_s, table.layers[1].lambda_J_per_s);
  EXPECT_GT(table.layers[1].lambda_J_per_s, table.layers[2].lambda_J_per_s);
}

TEST(PolicyLadder, ARungBelowTheFlatOutRunNamesItsOffset) {
  const Section s;
  const dp::SectionEngine engine(s.train, s.route, s.coarse());
  PolicyLadderOptions options;
  options.nominal_time_s = 110.0;
  options.time_offsets_s = {0.0, -40.0};
  try {
    build_policy_ladder(engine, {}, options);
    ADD_FAILURE() << "a 70 s rung was accepted";
  } catch (const LadderTimeError& e) {
    EXPECT_DOUBLE_EQ(e.offset_s(), -40.0);
    EXPECT_GT(e.minimum_s(), 70.0);
    EXPECT_NE(std::string(e.what()).find("minimum running time"), std::string::npos);
  }
  options.time_offsets_s = {0.0, 0.0};
  EXPECT_THROW(build_policy_ladder(engine, {}, options), std::invalid_argument);
}

}  // namespace
}  // namespace ecorail::policy
