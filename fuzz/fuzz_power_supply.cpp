// Power-supply TOML (the DC network of the timetable's network model): parsed and validated.
#include "fuzz_support.hpp"
#include "power/supply_loader.hpp"

using namespace ecorail;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  fuzz::refuse_cleanly(
      [&] { power::parse_power_supply(fuzz::as_text(data, size), "supply.toml"); });
  return 0;
}
