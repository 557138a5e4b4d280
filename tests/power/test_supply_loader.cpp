// Reading power-supply files: the shipped example reads as written, and every bad field is one
// InputError naming the key (and its line) and what was expected.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "data/input_error.hpp"
#include "power/supply_loader.hpp"

namespace ecorail::power {
namespace {

const std::string kGood = R"(name = "test"
[trains]
max_voltage_V = 900.0
min_voltage_V = 500.0
auxiliary_power_kW = 150.0

[[substations]]
name = "S1"
position_m = 0.0
no_load_voltage_V = 835.0
internal_resistance_ohm = 0.015

[[substations]]
name = "S2"
position_m = 4000.0
no_load_voltage_V = 835.0
internal_resistance_ohm = 0.015
reversible = true

[[conductors]]
from_m = 0.0
conductor_ohm_per_km = 0.008
return_ohm_per_km = 0.015
)";

TEST(SupplyLoader, ReadsTheShippedExample) {
  const PowerSupply s =
      load_power_supply(std::string(ECORAIL_SOURCE_DIR) + "/data/contest/power_supply.toml");
  std::string why;
  EXPECT_TRUE(s.IsValid(&why)) << why;
  ASSERT_EQ(s.substations.size(), 7u);
  EXPECT_EQ(s.substations.back().position_m, 22728.0);
  EXPECT_EQ(s.auxiliary_power_W, 150e3);
  EXPECT_FALSE(s.substations.front().reversible);
  // 23 mOhm/km loop resistance: 4.706 km to SS2.
  EXPECT_NEAR(s.loop_resistance_to_ohm(4706.0), 0.023 * 4.706, 1e-15);
}

TEST(SupplyLoader, ReadsEveryField) {
  const PowerSupply s = parse_power_supply(kGood, "good.toml");
  EXPECT_EQ(s.name, "test");
  EXPECT_TRUE(s.substations[1].reversible);
  EXPECT_EQ(s.min_train_voltage_V, 500.0);
  EXPECT_EQ(s.conductors[0].return_ohm_per_km, 0.015);
}

TEST(SupplyLoader, ResistanceChangesAlongTheLine) {
  PowerSupply s = parse_power_supply(kGood, "good.toml");
  s.conductors.push_back({1000.0, 0.0, 0.0});
  s.conductors.push_back({2000.0, 0.1, 0.1});
  EXPECT_NEAR(s.loop_resistance_to_ohm(500.0), 0.0115, 1e-15);
  EXPECT_EQ(s.loop_resistance_to_ohm(1500.0), s.loop_resistance_to_ohm(1000.0));
  EXPECT_NEAR(s.loop_resistance_to_ohm(2500.0), 0.023 + 0.1, 1e-15);
}

TEST(SupplyLoader, EveryBadFieldIsNamed) {
  // (text to replace, replacement, the field the error must name)
  const std::vector<std::tuple<std::string, std::string, std::string>> cases = {
      {"max_voltage_V = 900.0", "max_voltage_V = 400.0", "trains.max_voltage_V"},
      {"min_voltage_V = 500.0", "min_voltage_V = -1.0", "trains.min_voltage_V"},
      {"auxiliary_power_kW = 150.0", "auxiliary_power_kW = -5.0", "trains.auxiliary_power_kW"},
      {"auxiliary_power_kW = 150.0", "auxiliary_power_kW = \"a lot\"", "trains.auxiliary_power_kW"},
      {"auxiliary_power_kW = 150.0", "", "trains.auxiliary_power_kW"},
      {"auxiliary_power_kW = 150.0", "auxiliary_power_kW = 150.0\ncolour = 1", "trains.colour"},
      {"position_m = 4000.0", "position_m = 0.0", "substations[2].position_m"},
      {"position_m = 4000.0", "position_m = -3.0", "substations[2].position_m"},
      {"name = \"S2\"", "name = \"S1\"", "substations[2].name"},
      {"name = \"S2\"", "", "substations[2].name"},
      {"no_load_voltage_V = 835.0\ninternal_resistance_ohm = 0.015\nreversible",
       "no_load_voltage_V = 950.0\ninternal_resistance_ohm = 0.015\nreversible",
       "substations[2].no_load_voltage_V"},
      {"internal_resistance_ohm = 0.015\nreversible", "internal_resistance_ohm = 0.0\nreversible",
       "substations[2].internal_resistance_ohm"},
      {"reversible = true", "reversible = 1", "substations[2].reversible"},
      {"from_m = 0.0", "from_m = 10.0", "conductors[1].from_m"},
      {"conductor_ohm_per_km = 0.008", "conductor_ohm_per_km = -0.008",
       "conductors[1].conductor_ohm_per_km"},
      {"return_ohm_per_km = 0.015", "return_ohm_per_km = nan", "conductors[1].return_ohm_per_km"},
      {"[[conductors]]\nfrom_m = 0.0\nconductor_ohm_per_km = 0.008\nreturn_ohm_per_km = 0.015\n",
       "", "conductors"},
      {"[trains]", "[train]", "train"},
  };
  for (const auto& [from, to, field] : cases) {
    std::string text = kGood;
    const auto at = text.find(from);
    ASSERT_NE(at, std::string::npos) << from;
    text.replace(at, from.size(), to);
    try {
      parse_power_supply(text, "bad.toml");
      ADD_FAILURE() << "accepted: " << to;
    } catch (const data::InputError& e) {
      EXPECT_EQ(e.field(), field) << e.what();
      EXPECT_EQ(e.file(), "bad.toml");
    }
  }
}

}  // namespace
}  // namespace ecorail::power
