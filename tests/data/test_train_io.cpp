#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "data/train_io.hpp"
#include "data_test_support.hpp"
#include "physics/units.hpp"

namespace ecorail::data {
namespace {

using test::expect_input_error;
using test::TempDir;
using test::write_file;

void expect_same_envelope(const physics::ForceEnvelope& a, const physics::ForceEnvelope& b) {
  EXPECT_EQ(a.is_table(), b.is_table());
  EXPECT_EQ(a.power_cap_kW(), b.power_cap_kW());
  ASSERT_EQ(a.pieces().size(), b.pieces().size());
  for (std::size_t i = 0; i < a.pieces().size(); ++i) {
    EXPECT_EQ(a.pieces()[i].from_kmh, b.pieces()[i].from_kmh);
    EXPECT_EQ(a.pieces()[i].to_kmh, b.pieces()[i].to_kmh);
    EXPECT_EQ(a.pieces()[i].coeffs_kN, b.pieces()[i].coeffs_kN);
  }
  ASSERT_EQ(a.points().size(), b.points().size());
  for (std::size_t i = 0; i < a.points().size(); ++i) {
    EXPECT_EQ(a.points()[i].speed_kmh, b.points()[i].speed_kmh);
    EXPECT_EQ(a.points()[i].force_kN, b.points()[i].force_kN);
  }
}

void expect_same_train(const physics::Train& a, const physics::Train& b) {
  EXPECT_EQ(a.name, b.name);
  EXPECT_EQ(a.mass_kg, b.mass_kg);
  EXPECT_EQ(a.rotating_mass_factor, b.rotating_mass_factor);
  EXPECT_EQ(a.gravity_m_s2, b.gravity_m_s2);
  EXPECT_EQ(a.max_speed_ms, b.max_speed_ms);
  EXPECT_EQ(a.max_accel_m_s2, b.max_accel_m_s2);
  EXPECT_EQ(a.max_decel_m_s2, b.max_decel_m_s2);
  EXPECT_EQ(a.traction_efficiency, b.traction_efficiency);
  EXPECT_EQ(a.regen_efficiency, b.regen_efficiency);
  EXPECT_EQ(a.davis.A, b.davis.A);
  EXPECT_EQ(a.davis.B, b.davis.B);
  EXPECT_EQ(a.davis.C, b.davis.C);
  expect_same_envelope(a.traction, b.traction);
  expect_same_envelope(a.braking, b.braking);
}

// A train unlike the reference one: point tables, a power cap, awkward numbers and name.
physics::Train odd_train() {
  physics::Train t;
  t.name = "odd \"train\" \\ with\ttab";
  t.mass_kg = 123456.789;
  t.rotating_mass_factor = 0.08;
  t.gravity_m_s2 = 9.80665;
  t.max_speed_ms = 23.456;
  t.max_accel_m_s2 = 0.7;
  t.max_decel_m_s2 = 1.1;
  t.traction_efficiency = 0.9;
  t.regen_efficiency = 0.6;
  t.davis = {1.0 / 3.0, 1e-5, 2.5e-7};
  t.traction = physics::ForceEnvelope::table({{0.0, 310.0}, {36.4, 300.1}, {90.0, 120.0}}, 2400.0);
  t.braking = physics::ForceEnvelope::piecewise({{0.0, 10.0, {100.0, 5.0}}, {10.0, 95.0, {150.0}}});
  return t;
}

TEST(TrainIo, DefaultTrainIsTheContestTrain) {
  const auto t = default_train();
  EXPECT_EQ(t.name, "contest EMU (2015 reference)");
  EXPECT_DOUBLE_EQ(t.mass_kg, 194295.0);
  EXPECT_EQ(t.rotating_mass_factor, 0.0);
  EXPECT_EQ(t.gravity_m_s2, 9.8);
  EXPECT_DOUBLE_EQ(t.max_speed_ms, 80.0 / 3.6);
  EXPECT_EQ(t.max_accel_m_s2, 1.0);
  EXPECT_EQ(t.max_decel_m_s2, 1.0);
  EXPECT_EQ(t.traction_efficiency, 1.0);
  EXPECT_EQ(t.regen_efficiency, 0.95);
  EXPECT_EQ(t.davis.A, 2.031);
  EXPECT_EQ(t.davis.B, 0.0622);
  EXPECT_EQ(t.davis.C, 0.001807);
  EXPECT_DOUBLE_EQ(t.traction.force_kN_at_kmh(30.0), 203.0);
  const double v = 70.0;
  EXPECT_NEAR(t.traction.force_kN_at_kmh(v),
              -0.002032 * v * v * v + 0.4928 * v * v - 42.13 * v + 1343, 1e-9);
  EXPECT_DOUBLE_EQ(t.braking.force_kN_at_kmh(50.0), 166.0);
  EXPECT_NEAR(t.braking.force_kN_at_kmh(78.0), 0.1343 * 78 * 78 - 25.07 * 78 + 1300, 1e-9);
  EXPECT_EQ(t.traction.power_cap_kW(), 0.0);
}

TEST(TrainIo, FileAndEmbeddedTrainAgree) {
  const auto file = load_train(test::contest_dir() / "train.toml");
  expect_same_train(file, default_train());
  EXPECT_EQ(train_checksum(file), train_checksum(default_train()));
}

TEST(TrainIo, RoundTripOfTheReferenceTrain) {
  const auto t = default_train();
  const std::string text = train_to_toml(t);
  const auto back = parse_train_toml(text, "roundtrip.toml");
  expect_same_train(t, back);
  EXPECT_EQ(train_to_toml(back), text);
  EXPECT_EQ(train_checksum(back), train_checksum(t));
  EXPECT_NE(text.find("mass_t = 194.295\n"), std::string::npos) << text;
  EXPECT_NE(text.find("max_speed_kmh = 80.0\n"), std::string::npos) << text;
}

TEST(TrainIo, RoundTripOfAnOddTrain) {
  const auto t = odd_train();
  const auto back = parse_train_toml(train_to_toml(t), "odd.toml");
  expect_same_train(t, back);
  EXPECT_EQ(train_checksum(back), train_checksum(t));
  EXPECT_NE(train_checksum(t), train_checksum(default_train()));
}

TEST(TrainIo, RoundTripOfRandomSiValues) {
  // Mass and maximum speed are stored in t and km/h and converted on reading (x 1000, / 3.6).
  // Not every double is the product of such a conversion, so a value a program computed comes
  // back exact when it can and otherwise one unit in the last place off; after one pass through
  // a file the train is a fixed point of writing and reading.
  std::mt19937_64 rng(42);
  // 100 t and up, 80 km/h at most (the reference envelopes' range, beyond which their
  // polynomials grow): the envelopes stay within the plausibility range of 20 m/s^2.
  std::uniform_real_distribution<double> mass(1e5, 1e6);
  std::uniform_real_distribution<double> speed(1.0, 22.2);
  auto t = default_train();
  int exact = 0;
  for (int i = 0; i < 2000; ++i) {
    t.mass_kg = mass(rng);
    t.max_speed_ms = speed(rng);
    const std::string text = train_to_toml(t);
    const auto back = parse_train_toml(text, "r.toml");
    exact += back.mass_kg == t.mass_kg && back.max_speed_ms == t.max_speed_ms;
    EXPECT_LE(std::abs(back.mass_kg - t.mass_kg), std::nextafter(t.mass_kg, 2e6) - t.mass_kg);
    EXPECT_LE(std::abs(back.max_speed_ms - t.max_speed_ms),
              std::nextafter(t.max_speed_ms, 200.0) - t.max_speed_ms);
    const std::string again = train_to_toml(back);
    const auto twice = parse_train_toml(again, "r.toml");
    ASSERT_EQ(twice.mass_kg, back.mass_kg);
    ASSERT_EQ(twice.max_speed_ms, back.max_speed_ms);
    ASSERT_EQ(train_to_toml(twice), again);
  }
  EXPECT_GT(exact, 1500);  // most values are reachable
}

TEST(TrainIo, SaveAndLoad) {
  TempDir tmp;
  const auto t = odd_train();
  save_train(t, tmp / "t.toml");
  expect_same_train(load_train(tmp / "t.toml"), t);
  // Overwrite in place; nothing else is left in the directory.
  save_train(default_train(), tmp / "t.toml");
  expect_same_train(load_train(tmp / "t.toml"), default_train());
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(tmp.path()),
                          std::filesystem::directory_iterator()),
            1);
}

TEST(TrainIo, GravityDefaultsTo9_8) {
  std::string text = train_to_toml(default_train());
  const auto pos = text.find("gravity_m_s2 = 9.8\n");
  ASSERT_NE(pos, std::string::npos);
  text.erase(pos, std::string("gravity_m_s2 = 9.8\n").size());
  EXPECT_EQ(parse_train_toml(text, "g.toml").gravity_m_s2, 9.8);
}

TEST(TrainIo, IntegersAreAcceptedAsNumbers) {
  std::string text = train_to_toml(default_train());
  const auto pos = text.find("max_speed_kmh = 80.0");
  ASSERT_NE(pos, std::string::npos);
  text.replace(pos, 20, "max_speed_kmh = 80");
  EXPECT_EQ(parse_train_toml(text, "i.toml").max_speed_ms, default_train().max_speed_ms);
}

// ---- errors ---------------------------------------------------------------------------------

class TrainErrors : public ::testing::Test {
 protected:
  // The reference train's TOML with one edit; from must occur.
  static std::string edited(const std::string& from, const std::string& to) {
    std::string text = std::string(test::read_file(test::contest_dir() / "train.toml"));
    const auto pos = text.find(from);
    EXPECT_NE(pos, std::string::npos) << from;
    if (pos != std::string::npos) text.replace(pos, from.size(), to);
    return text;
  }
  static void expect_error(const std::string& from, const std::string& to, const std::string& field,
                           std::initializer_list<std::string> what) {
    const std::string text = edited(from, to);
    expect_input_error([&] { parse_train_toml(text, "bad/train.toml"); }, "bad/train.toml", 0,
                       field, what);
  }
};

TEST_F(TrainErrors, MissingFile) {
  TempDir tmp;
  expect_input_error([&] { load_train(tmp / "none.toml"); }, (tmp / "none.toml").string(), 0, "",
                     {"no such file"});
}

TEST_F(TrainErrors, MissingKey) {
  expect_error("mass_t = 194.295\n", "", "mass_t", {"a number", "missing"});
  expect_error("C = 0.001807\n", "", "davis.C", {"a number", "missing"});
  expect_error("name = \"contest EMU (2015 reference)\"\n", "", "name", {"a string"});
  expect_error("[braking]", "[brakes]", "brakes", {"one of the keys"});
  const std::string text = test::read_file(test::contest_dir() / "train.toml");
  expect_error(text.substr(text.find("[braking]")), "", "braking",
               {"a table [braking]", "missing"});
}

TEST_F(TrainErrors, WrongType) {
  expect_error("mass_t = 194.295", "mass_t = \"heavy\"", "mass_t",
               {"a number", "the string \"heavy\""});
  expect_error("regen_efficiency = 0.95", "regen_efficiency = true", "regen_efficiency",
               {"a number", "boolean"});
  expect_error("coeffs_kN = [203.0]", "coeffs_kN = 203.0", "traction.segments[1].coeffs_kN",
               {"array"});
  expect_error("coeffs_kN = [166.0]", "coeffs_kN = [166.0, \"x\"]",
               "braking.segments[1].coeffs_kN[2]", {"a number"});
}

TEST_F(TrainErrors, BadValues) {
  expect_error("mass_t = 194.295", "mass_t = 0", "mass_t", {"above 0", "got 0"});
  expect_error("mass_t = 194.295", "mass_t = -5.0", "mass_t", {"above 0", "got -5"});
  expect_error("regen_efficiency = 0.95", "regen_efficiency = 1.5", "regen_efficiency",
               {"(0, 1]", "got 1.5"});
  expect_error("traction_efficiency = 1.0", "traction_efficiency = 0.0", "traction_efficiency",
               {"(0, 1]", "got 0"});
  expect_error("rotating_mass_factor = 0.0", "rotating_mass_factor = -0.1", "rotating_mass_factor",
               {"at least 0", "got -0.1"});
  expect_error("max_speed_kmh = 80.0", "max_speed_kmh = nan", "max_speed_kmh", {"finite"});
}

TEST_F(TrainErrors, SegmentsMustBeContiguousFromZero) {
  expect_error("{ from_kmh = 0.0, to_kmh = 51.5", "{ from_kmh = 1.0, to_kmh = 51.5",
               "traction.segments[1].from_kmh", {"contiguous from 0", "got 1"});
  expect_error("{ from_kmh = 51.5, to_kmh = 80.0", "{ from_kmh = 52.0, to_kmh = 80.0",
               "traction.segments[2].from_kmh", {"previous to_kmh 51.5", "got 52"});
  expect_error("{ from_kmh = 77.0, to_kmh = 80.0", "{ from_kmh = 77.0, to_kmh = 77.0",
               "braking.segments[2].to_kmh", {"above from_kmh 77"});
}

TEST_F(TrainErrors, EnvelopeForm) {
  expect_error("[braking]\n", "[braking]\npoints = [[0.0, 166.0]]\n", "braking", {"got both"});
  expect_error("[braking]\nsegments", "[braking]\nsegs", "braking.segs", {"one of the keys"});
  expect_error("[traction]\n", "[traction]\npower_cap_kW = -1.0\n", "traction.power_cap_kW",
               {"at least 0"});
}

TEST_F(TrainErrors, PointTables) {
  const std::string head = "[braking]\n";
  const std::string body = test::read_file(test::contest_dir() / "train.toml");
  const std::string braking = body.substr(body.find(head));
  expect_error(braking, "[braking]\npoints = [[0.0, 166.0], [50.0, 160.0], [40.0, 100.0]]\n",
               "braking.points[3][1]", {"above the previous point's 50", "got 40"});
  expect_error(braking, "[braking]\npoints = [[0.0, 166.0], [50.0]]\n", "braking.points[2]",
               {"a pair"});
  expect_error(braking, "[braking]\npoints = [[0.0, -1.0]]\n", "braking.points[1][2]",
               {"at least 0 kN"});
}

TEST_F(TrainErrors, UnknownKey) {
  expect_error("gravity_m_s2 = 9.8", "gravity = 9.8", "gravity", {"one of the keys"});
  expect_error("A = 2.031", "A0 = 2.031", "davis.A0", {"one of the keys"});
}

TEST_F(TrainErrors, SyntaxError) {
  expect_error("mass_t = 194.295", "mass_t = = 194.295", "", {"valid TOML", "line 4"});
}

}  // namespace
}  // namespace ecorail::data
