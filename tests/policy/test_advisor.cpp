// The Advisor on the default grid of A6 -> A7: it refuses tables made for another line or train
// (naming the checksum that differs), reproduces the table's cost-to-go and time-to-go at grid
// nodes, stays close to the table's own interpolation between them, gives sensible advice at the
// start and on the final braking curve, and picks ladder layers by the time left.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <random>

#include "data/line_loader.hpp"
#include "data/route_builder.hpp"
#include "data/train_io.hpp"
#include "dp/time_target.hpp"
#include "physics/units.hpp"
#include "policy/advisor.hpp"
#include "policy/ladder.hpp"

namespace ecorail {
namespace {

struct Fixture {
  data::Line line = data::default_line();
  physics::Train train = data::default_train();
  policy::PolicyTable table;

  Fixture() {
    const physics::Route route = data::build_route(line, "A6", "A7", train);
    const dp::SectionEngine engine(train, route, {});
    table =
        policy::make_policy_table(engine, line.name, line.checksum(), data::train_checksum(train));
    for (double offset : {-5.0, 0.0, 5.0}) {
      // Searched as the ladder searches a layer's price (to 0.05 s, no trim to lean on).
      const dp::TimeSearchResult found =
          dp::solve_for_time(engine, 110.0 + offset, policy::layer_search());
      policy::PolicyLayer layer = policy::build_policy_layer(engine, found.run.lambda);
      layer.time_offset_s = offset;
      layer.target_time_s = 110.0 + offset;
      table.layers.push_back(std::move(layer));
    }
  }
};

const Fixture& fixture() {
  static const Fixture f;
  return f;
}

std::string mismatch_of(const policy::PolicyTable& table, const data::Line& line,
                        const physics::Train& train) {
  try {
    policy::Advisor advisor(table, line, train);
  } catch (const policy::PolicyMismatchError& e) {
    return e.what();
  }
  return "";
}

TEST(Advisor, RefusesAnotherLineOrTrainNamingTheChecksum) {
  const Fixture& f = fixture();
  EXPECT_EQ(mismatch_of(f.table, f.line, f.train), "");

  data::Line other_line = f.line;
  other_line.gradients.front().value += 0.1;
  const std::string line_msg = mismatch_of(f.table, other_line, f.train);
  std::printf("wrong line: %s\n", line_msg.c_str());
  EXPECT_NE(line_msg.find("line checksum differs"), std::string::npos) << line_msg;
  EXPECT_EQ(line_msg.find("train checksum"), std::string::npos) << line_msg;

  physics::Train other_train = f.train;
  other_train.mass_kg *= 1.05;
  const std::string train_msg = mismatch_of(f.table, f.line, other_train);
  std::printf("wrong train: %s\n", train_msg.c_str());
  EXPECT_NE(train_msg.find("train checksum differs"), std::string::npos) << train_msg;
  EXPECT_EQ(train_msg.find("line checksum"), std::string::npos) << train_msg;

  const std::string both = mismatch_of(f.table, other_line, other_train);
  EXPECT_NE(both.find("line checksum differs"), std::string::npos);
  EXPECT_NE(both.find("train checksum differs"), std::string::npos);
}

TEST(Advisor, LoadChecksTheFileAndTheTrain) {
  const Fixture& f = fixture();
  const auto dir = std::filesystem::temp_directory_path() / "ecorail_advisor_test";
  std::filesystem::create_directories(dir);
  const auto path = dir / "a6a7.bin";
  policy::save_policy(f.table, path);
  const policy::Advisor advisor = policy::Advisor::load(path, f.line, f.train);
  EXPECT_EQ(advisor.table().layers.size(), 3u);
  EXPECT_EQ(advisor.layer(), 1);  // the nominal layer (offset 0)
  physics::Train other = f.train;
  other.davis.A += 0.01;
  EXPECT_THROW(policy::Advisor::load(path, f.line, other), policy::PolicyMismatchError);
  std::filesystem::resize_file(path, std::filesystem::file_size(path) - 100);
  EXPECT_THROW(policy::Advisor::load(path, f.line, f.train), policy::PolicyFormatError);
  std::filesystem::remove_all(dir);
}

TEST(Advisor, ReproducesTheTableAtGridNodes) {
  const Fixture& f = fixture();
  const policy::Advisor advisor(f.table, f.line, f.train);
  const policy::PolicyLayer& L = f.table.layers[1];
  int nodes = 0, same_control = 0;
  double worst = 0.0;
  for (int i = 0; i + 1 < f.table.stage_count(); i += 3) {
    for (std::uint32_t n = f.table.stage_offset[i]; n < f.table.stage_offset[i + 1]; ++n) {
      const policy::Advice a = advisor.advise(f.table.position_m[i], f.table.speed_ms[n]);
      ASSERT_TRUE(a.feasible);
      const double rel = std::abs(a.cost_to_go_J - L.cost_to_go_J[n]) / L.cost_to_go_J[n];
      worst = std::max(worst, rel);
      ASSERT_LT(rel, 1e-9) << "stage " << i << " node " << n;
      ASSERT_NEAR(a.time_to_go_s, L.time_to_go_s[n], 1e-6) << "stage " << i << " node " << n;
      ++nodes;
      if (static_cast<std::uint8_t>(a.control) == L.control[n]) ++same_control;
    }
  }
  std::printf(
      "%d nodes: cost-to-go worst relative difference %.2e; stored u* chosen at %d "
      "(the rest are ties, e.g. every control clamped onto a braking curve)\n",
      nodes, worst, same_control);
}

TEST(Advisor, BetweenNodesStaysCloseToTheTableInterpolation) {
  const Fixture& f = fixture();
  const policy::Advisor advisor(f.table, f.line, f.train);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> pos(0.0, f.table.route_length_m - 1.0);
  const double final_approach_m = f.table.route_length_m - 100.0;
  double worst_run = 0.0, worst_end = 0.0;
  int n = 0;
  for (int k = 0; k < 2000; ++k) {
    const double s = pos(rng);
    // Only where both neighbouring stages have nodes at v: elsewhere (just past the end of a
    // lower limit, or in the last step before the stop) the bilinear rule clamps to the top
    // node and the look-ahead is the only meaningful answer.
    const int next = f.table.next_stage_after(s);
    const double top = std::min(f.table.speed_ms[f.table.stage_offset[next] - 1],
                                f.table.speed_ms[f.table.stage_offset[next + 1] - 1]);
    if (top < 1.0) continue;
    const double v = std::uniform_real_distribution<double>(0.5, top)(rng);
    const policy::Advice a = advisor.advise(s, v);
    ASSERT_TRUE(a.feasible);
    const double table_J = f.table.cost_to_go_J(1, s, v);
    const double rel = std::abs(a.cost_to_go_J - table_J) / table_J;
    double& worst = s < final_approach_m ? worst_run : worst_end;
    worst = std::max(worst, rel);
    ++n;
  }
  std::printf(
      "%d random states: look-ahead vs bilinear table cost-to-go, worst %.3f %% before "
      "the last 100 m, %.3f %% in them (crawling states where J ~ 1/v)\n",
      n, 100.0 * worst_run, 100.0 * worst_end);
  EXPECT_GT(n, 1900);
  EXPECT_LT(worst_run, 0.01);
  EXPECT_LT(worst_end, 0.05);
}

TEST(Advisor, AdviceAtTheStartOnTheBrakingCurveAndAtTheStop) {
  const Fixture& f = fixture();
  const policy::Advisor advisor(f.table, f.line, f.train);
  const policy::Advice start = advisor.advise(0.0, 0.0);
  EXPECT_EQ(start.control, physics::Control::MaxTraction);
  EXPECT_EQ(start.regime, physics::Regime::FullTraction);
  EXPECT_GT(start.force_N, 190e3);
  EXPECT_NEAR(start.time_to_go_s, 110.0, 1.0);
  // Above the braking curve for the stop every control is clamped: the advice says brake.
  const policy::Advice late = advisor.advise(1300.0, units::kmh_to_ms(40.0));
  EXPECT_EQ(late.control, physics::Control::MaxBrake);
  EXPECT_EQ(late.regime, physics::Regime::FullBrake);
  EXPECT_NEAR(late.force_N, -166e3, 1.0);
  EXPECT_DOUBLE_EQ(late.energy_to_go_J, 0.0);
  const policy::Advice stop = advisor.advise(f.table.route_length_m, 0.0);
  EXPECT_EQ(stop.cost_to_go_J, 0.0);
}

TEST(Advisor, LadderLayersAreOrderedAndSelectedByTimeLeft) {
  const Fixture& f = fixture();
  policy::Advisor advisor(f.table, f.line, f.train);
  const auto& layers = f.table.layers;
  EXPECT_GT(layers[0].lambda_J_per_s, layers[1].lambda_J_per_s);  // running early costs more
  EXPECT_GT(layers[1].lambda_J_per_s, layers[2].lambda_J_per_s);
  for (const auto& L : layers) EXPECT_NEAR(L.planned_time_s, L.target_time_s, 0.1);
  EXPECT_LT(layers[2].planned_energy_J, layers[1].planned_energy_J);
  EXPECT_EQ(advisor.layer_for_time(0.0, 0.0, 104.0), 0);
  EXPECT_EQ(advisor.layer_for_time(0.0, 0.0, 110.5), 1);
  EXPECT_EQ(advisor.layer_for_time(0.0, 0.0, 118.0), 2);
  advisor.select_layer(2);
  EXPECT_EQ(advisor.layer(), 2);
  EXPECT_THROW(advisor.select_layer(3), std::out_of_range);
}

}  // namespace
}  // namespace ecorail
