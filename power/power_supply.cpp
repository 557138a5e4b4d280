#include "power/power_supply.hpp"

#include <cmath>

namespace ecorail::power {

namespace {

bool finite_at_least(double v, double lo) {
  return std::isfinite(v) && v >= lo;
}

}  // namespace

bool PowerSupply::IsValid(std::string* error) const {
  auto fail = [&](const std::string& why) {
    if (error) *error = why;
    return false;
  };
  if (!(std::isfinite(min_train_voltage_V) && min_train_voltage_V > 0.0))
    return fail("trains.min_voltage_V: expected a voltage > 0 V");
  if (!(std::isfinite(max_train_voltage_V) && max_train_voltage_V > min_train_voltage_V))
    return fail("trains.max_voltage_V: expected a voltage above trains.min_voltage_V");
  if (!finite_at_least(auxiliary_power_W, 0.0))
    return fail("trains.auxiliary_power_kW: expected a power >= 0");
  if (substations.empty()) return fail("substations: expected at least one substation");
  for (std::size_t i = 0; i < substations.size(); ++i) {
    const Substation& s = substations[i];
    const std::string at = "substations[" + std::to_string(i + 1) + "].";
    if (!finite_at_least(s.position_m, 0.0))
      return fail(at + "position_m: expected a position >= 0 m");
    if (i > 0 && !(s.position_m > substations[i - 1].position_m))
      return fail(at + "position_m: expected a position beyond the previous substation's");
    if (!(std::isfinite(s.no_load_voltage_V) && s.no_load_voltage_V > min_train_voltage_V &&
          s.no_load_voltage_V < max_train_voltage_V))
      return fail(at + "no_load_voltage_V: expected a voltage between trains.min_voltage_V and " +
                  "trains.max_voltage_V");
    if (!(std::isfinite(s.internal_resistance_ohm) && s.internal_resistance_ohm > 0.0))
      return fail(at + "internal_resistance_ohm: expected a resistance > 0 ohm");
  }
  if (conductors.empty()) return fail("conductors: expected at least one segment");
  for (std::size_t i = 0; i < conductors.size(); ++i) {
    const ConductorSegment& c = conductors[i];
    const std::string at = "conductors[" + std::to_string(i + 1) + "].";
    if (i == 0 && c.from_m != 0.0) return fail(at + "from_m: expected the first segment from 0 m");
    if (i > 0 && !(std::isfinite(c.from_m) && c.from_m > conductors[i - 1].from_m))
      return fail(at + "from_m: expected a position beyond the previous segment's");
    if (!finite_at_least(c.conductor_ohm_per_km, 0.0))
      return fail(at + "conductor_ohm_per_km: expected a resistance >= 0");
    if (!finite_at_least(c.return_ohm_per_km, 0.0))
      return fail(at + "return_ohm_per_km: expected a resistance >= 0");
  }
  return true;
}

double PowerSupply::loop_resistance_to_ohm(double position_m) const {
  double r = 0.0;
  for (std::size_t i = 0; i < conductors.size(); ++i) {
    const ConductorSegment& c = conductors[i];
    const double per_m = (c.conductor_ohm_per_km + c.return_ohm_per_km) / 1000.0;
    const bool last = i + 1 == conductors.size();
    if (i == 0 && position_m < c.from_m) return per_m * (position_m - c.from_m);
    const double end = last ? position_m : std::min(position_m, conductors[i + 1].from_m);
    if (end <= c.from_m) break;
    r += per_m * (end - c.from_m);
    if (last || position_m <= conductors[i + 1].from_m) break;
  }
  return r;
}

}  // namespace ecorail::power
