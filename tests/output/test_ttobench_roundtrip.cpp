// TTOBench JSON writing: read -> write -> read gives the same Line::checksum and
// train_checksum for every track and train of the shared TTOBench copy (and for hand-made
// clothoids and tunnels); the reference line, written and read back, gives the same routes.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "data/line_loader.hpp"
#include "data/route_builder.hpp"
#include "data/train_io.hpp"
#include "data/ttobench_io.hpp"
#include "output/ttobench_writer.hpp"

namespace ecorail::data {
namespace {

const std::filesystem::path kTtobench =
    std::filesystem::path(ECORAIL_SHARED_DIR) / "data" / "ttobench";

std::string read(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream out;
  out << in.rdbuf();
  return out.str();
}

TEST(TtobenchRoundTrip, EveryTrackKeepsItsChecksum) {
  if (!std::filesystem::exists(kTtobench / "tracks")) GTEST_SKIP() << "no TTOBench copy";
  int tracks = 0;
  for (const auto& entry : std::filesystem::directory_iterator(kTtobench / "tracks")) {
    if (entry.path().extension() != ".json") continue;
    const Line a = line_from_ttobench(read(entry.path()), entry.path().string());
    const std::string text = output::line_to_ttobench(a, entry.path().stem().string());
    const Line b = line_from_ttobench(text, "written");
    EXPECT_EQ(a.checksum(), b.checksum()) << entry.path();
    EXPECT_EQ(text, output::line_to_ttobench(b, entry.path().stem().string())) << entry.path();
    ++tracks;
  }
  EXPECT_GE(tracks, 16);
}

TEST(TtobenchRoundTrip, EveryTrainKeepsItsChecksum) {
  if (!std::filesystem::exists(kTtobench / "trains")) GTEST_SKIP() << "no TTOBench copy";
  int trains = 0;
  int through_toml = 0;
  for (const auto& entry : std::filesystem::directory_iterator(kTtobench / "trains")) {
    const physics::Train a = train_from_ttobench(read(entry.path()), entry.path().string());
    const physics::Train b = train_from_ttobench(output::train_to_ttobench(a), "written");
    EXPECT_EQ(train_checksum(a), train_checksum(b)) << entry.path();
    // The TOML form carries the new terms too (pneumatic brake, length, tunnel drag). A train
    // without comfort limits has none in TOML either, which the plausibility check of TOML
    // trains (data/plausibility) refuses, so only trains with both limits go through TOML.
    if (std::isfinite(a.max_accel_m_s2) && std::isfinite(a.max_decel_m_s2)) {
      EXPECT_EQ(train_checksum(a), train_checksum(parse_train_toml(train_to_toml(a), "toml")))
          << entry.path();
      ++through_toml;
    }
    ++trains;
  }
  EXPECT_EQ(trains, 4);
  EXPECT_GE(through_toml, 2);  // the FLIRT (length, tunnel drag) and the KISS
}

TEST(TtobenchRoundTrip, ReferenceLineGivesTheSameRoutes) {
  const Line line = default_line();
  const std::string text = output::line_to_ttobench(line, "contest");
  const Line back = line_from_ttobench(text, "written");
  EXPECT_EQ(back.stations.size(), line.stations.size());
  const physics::Train train = default_train();
  for (const auto& [from, to] : {std::pair{"A1", "A2"}, {"A6", "A7"}, {"A14", "A13"}}) {
    const physics::Route r0 = build_route(line, from, to, train);
    const physics::Route r1 = build_route(back, from, to, train);
    ASSERT_EQ(r0.segments().size(), r1.segments().size()) << from << to;
    for (std::size_t i = 0; i < r0.segments().size(); ++i) {
      const auto& s0 = r0.segments()[i];
      const auto& s1 = r1.segments()[i];
      EXPECT_NEAR(s0.start_m, s1.start_m, 1e-9);
      EXPECT_NEAR(s0.end_m, s1.end_m, 1e-9);
      EXPECT_EQ(s0.gradient_permille, s1.gradient_permille);
      EXPECT_NEAR(s0.track_N_per_kN(), s1.track_N_per_kN(), 1e-12);
      EXPECT_EQ(s0.speed_limit_ms, s1.speed_limit_ms);
    }
  }
  // Written again, the text is the same (the second read is a fixed point).
  EXPECT_EQ(output::line_to_ttobench(back, "contest"), text);
}

TEST(TtobenchRoundTrip, TrainsTtobenchCannotStateAreRefused) {
  // The reference train's traction is a cubic above 51.5 km/h, not a force under a power cap.
  EXPECT_THROW(output::train_to_ttobench(default_train()), std::invalid_argument);
}

}  // namespace
}  // namespace ecorail::data
