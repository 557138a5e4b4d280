// Efficiency maps and auxiliary power in the train TOML (docs/formats.md): read, validated with
// the field named, and written back so that the text (and so the checksum) reads back the same.
#include <gtest/gtest.h>

#include <string>

#include "data/embedded.hpp"
#include "data/input_error.hpp"
#include "data/train_io.hpp"
#include "data_test_support.hpp"

namespace ecorail::data {
namespace {

using test::expect_input_error;

// The reference train's text with top-level lines and tables added.
std::string reference_with(const std::string& top, const std::string& tables) {
  std::string text(embedded::find("train.toml"));
  const std::size_t davis = text.find("[davis]");
  return text.substr(0, davis) + top + "\n" + text.substr(davis) + "\n" + tables;
}

const char* kMaps =
    "[traction_efficiency_map]\n"
    "speeds_kmh = [0.0, 40.0, 80.0]\n"
    "forces_kN = [0.0, 200.0]\n"
    "efficiency = [[0.80, 0.70], [0.90, 0.85], [0.92, 0.88]]\n"
    "[regen_efficiency_map]\n"
    "speeds_kmh = [0.0, 80.0]\n"
    "forces_kN = [0.0, 170.0]\n"
    "efficiency = [[0.5, 0.6], [0.9, 0.8]]\n";

TEST(EfficiencyMapIo, ReadsMapsAndAuxiliaryPowerAndInterpolatesBilinearly) {
  const physics::Train t =
      parse_train_toml(reference_with("auxiliary_power_kW = 150.0", kMaps), "t.toml");
  EXPECT_DOUBLE_EQ(t.auxiliary_power_W, 150000.0);
  ASSERT_TRUE(t.has_efficiency_maps());
  const double v20 = 20.0 / 3.6, v40 = 40.0 / 3.6, v60 = 60.0 / 3.6;
  // By hand: corners, edges, the middle of a cell, clamped outside, force by magnitude.
  EXPECT_NEAR(t.traction_efficiency_at(v40, 200e3), 0.85, 1e-12);
  EXPECT_NEAR(t.traction_efficiency_at(v20, 0.0), 0.85, 1e-12);          // (0.80 + 0.90) / 2
  EXPECT_NEAR(t.traction_efficiency_at(v60, 100e3), 0.8875, 1e-12);      // mean of 4 corners
  EXPECT_NEAR(t.traction_efficiency_at(200.0 / 3.6, 1e9), 0.88, 1e-12);  // clamped
  EXPECT_NEAR(t.traction_efficiency_at(v60, -100e3), 0.8875, 1e-12);     // |force|
  EXPECT_NEAR(t.regen_efficiency_at(v40, 85e3), 0.7, 1e-12);             // (0.5+0.6+0.9+0.8)/4
  // The constants stand when no map is given.
  const physics::Train plain = default_train();
  EXPECT_FALSE(plain.has_efficiency_maps());
  EXPECT_EQ(plain.traction_efficiency_at(v40, 1e5), plain.traction_efficiency);
}

TEST(EfficiencyMapIo, WritesBackToTheSameTextAndChecksum) {
  const physics::Train t =
      parse_train_toml(reference_with("auxiliary_power_kW = 150.0", kMaps), "t.toml");
  const std::string text = train_to_toml(t);
  const physics::Train again = parse_train_toml(text, "again.toml");
  EXPECT_EQ(train_to_toml(again), text);
  EXPECT_EQ(train_checksum(again), train_checksum(t));
  EXPECT_EQ(again.traction_efficiency_map.values, t.traction_efficiency_map.values);
  EXPECT_EQ(again.regen_efficiency_map.speeds_ms, t.regen_efficiency_map.speeds_ms);
  EXPECT_EQ(again.auxiliary_power_W, t.auxiliary_power_W);
  // A train without either keeps its text (and so its checksum and every cache key).
  const physics::Train plain = default_train();
  EXPECT_EQ(train_to_toml(plain).find("efficiency_map"), std::string::npos);
  EXPECT_EQ(train_to_toml(plain).find("auxiliary"), std::string::npos);
  EXPECT_NE(train_checksum(plain), train_checksum(t));
}

// A fuzz finding: a map speed of 84 km/h read as 84 * (1/3.6) and written by inverting
// 84 / 3.6 differs in the last bit, so the text would drift on every round trip. The reader
// uses the conversions the writer inverts.
TEST(EfficiencyMapIo, MapAxesReadBackExactly) {
  const physics::Train t = parse_train_toml(
      reference_with("",
                     "[traction_efficiency_map]\nspeeds_kmh = [0.0, 40.0, 84.0, 97.3]\n"
                     "forces_kN = [0.0, 0.3, 200.0]\nefficiency = [[0.8, 0.8, 0.7], "
                     "[0.9, 0.9, 0.85], [0.92, 0.9, 0.88], [0.9, 0.9, 0.9]]\n"),
      "t.toml");
  const physics::Train again = parse_train_toml(train_to_toml(t), "again.toml");
  EXPECT_EQ(again.traction_efficiency_map.speeds_ms, t.traction_efficiency_map.speeds_ms);
  EXPECT_EQ(again.traction_efficiency_map.forces_N, t.traction_efficiency_map.forces_N);
  EXPECT_EQ(train_to_toml(again), train_to_toml(t));
  EXPECT_NE(train_to_toml(t).find("84.0, 97.3]"), std::string::npos) << train_to_toml(t);
}

TEST(EfficiencyMapIo, BadMapsAndAuxiliaryPowerNameTheField) {
  const auto parse = [](const std::string& top, const std::string& tables) {
    return [=] { parse_train_toml(reference_with(top, tables), "t.toml"); };
  };
  expect_input_error(parse("auxiliary_power_kW = -5.0", ""), "t.toml", 0, "auxiliary_power_kW");
  expect_input_error(parse("auxiliary_power_kW = 1e9", ""), "t.toml", 0, "auxiliary_power_kW");
  const std::string head = "[traction_efficiency_map]\n";
  expect_input_error(parse("", head + "speeds_kmh = [0.0, 80.0]\nforces_kN = [0.0, 100.0]\n"
                                      "efficiency = [[0.9, 0.9], [0.9, 1.5]]\n"),
                     "t.toml", 0, "traction_efficiency_map.efficiency[2][2]");
  expect_input_error(parse("", head + "speeds_kmh = [0.0, 80.0, 40.0]\nforces_kN = [0.0, 1.0]\n"
                                      "efficiency = [[0.9, 0.9], [0.9, 0.9], [0.9, 0.9]]\n"),
                     "t.toml", 0, "traction_efficiency_map.speeds_kmh[3]");
  expect_input_error(parse("", head + "speeds_kmh = [0.0, 80.0]\nforces_kN = [0.0, 100.0]\n"
                                      "efficiency = [[0.9, 0.9]]\n"),
                     "t.toml", 0, "traction_efficiency_map.efficiency");
  expect_input_error(parse("", head + "speeds_kmh = [0.0, 80.0]\nforces_kN = [0.0, 100.0]\n"
                                      "efficiency = [[0.9, 0.9], [0.9]]\n"),
                     "t.toml", 0, "traction_efficiency_map.efficiency[2]");
  expect_input_error(parse("", head + "speeds_kmh = [0.0]\nforces_kN = [0.0, 100.0]\n"
                                      "efficiency = [[0.9, 0.9]]\n"),
                     "t.toml", 0, "traction_efficiency_map.speeds_kmh");
}

}  // namespace
}  // namespace ecorail::data
