// Reading a line's power supply from TOML (format in docs/formats.md, example in
// data/contest/power_supply.toml). Every field is checked: a missing or mistyped key, an unknown
// key, a value out of range or out of order is one data::InputError naming the file, the line of
// the TOML table it sits in and the key (substations[2].position_m), and saying what was
// expected; the program prints it and exits with code 2.
#pragma once

#include <string>
#include <string_view>

#include "power/power_supply.hpp"

namespace ecorail::power {

PowerSupply parse_power_supply(std::string_view text, const std::string& file);
PowerSupply load_power_supply(const std::string& file);

}  // namespace ecorail::power
