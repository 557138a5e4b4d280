#include "energy/model_options.hpp"

#include <cmath>

namespace ecorail::energy {

std::string_view overlap_variant_name(OverlapVariant v) {
  return v == OverlapVariant::Either ? "either" : "ahead";
}

std::optional<OverlapVariant> overlap_variant_from_name(std::string_view name) {
  if (name == "ahead") return OverlapVariant::Ahead;
  if (name == "either") return OverlapVariant::Either;
  return std::nullopt;
}

bool EnergyModelOptions::IsValid(std::string* error) const {
  auto fail = [&](const std::string& why) {
    if (error) *error = why;
    return false;
  };
  if (!(std::isfinite(time_step_s) && time_step_s >= 1e-4 && time_step_s <= 1.0))
    return fail("time_step_s: expected 0.0001 to 1 s");
  const double ticks = 1.0 / time_step_s;
  if (std::fabs(ticks - std::round(ticks)) > 1e-6 * ticks)
    return fail("time_step_s: expected a step that divides one second (1, 0.5, 0.1, 0.01, ...)");
  double last = 0.0;
  for (double b : section_boundaries_m) {
    if (!(std::isfinite(b) && b > last))
      return fail("section_boundaries_m: expected increasing positions > 0 m");
    last = b;
  }
  if (power_supply) {
    std::string why;
    if (!power_supply->IsValid(&why)) return fail("power_supply: " + why);
  }
  if (!(std::isfinite(traction_efficiency) && traction_efficiency > 0.0 &&
        traction_efficiency <= 1.0))
    return fail("traction_efficiency: expected a value in (0, 1]");
  return true;
}

int EnergyModelOptions::ticks_per_second() const {
  return static_cast<int>(std::lround(1.0 / time_step_s));
}

std::string FleetLimits::departures_problem(const std::vector<int>& t) const {
  if (static_cast<int>(t.size()) != trains)
    return std::to_string(t.size()) + " departures, expected " + std::to_string(trains);
  if (t.empty()) return "";
  if (t.front() != 0) return "the first departure is at " + std::to_string(t.front()) + " s, not 0";
  if (t.back() != span_s)
    return "the last departure is at " + std::to_string(t.back()) + " s, not the span " +
           std::to_string(span_s) + " s";
  for (std::size_t k = 1; k < t.size(); ++k) {
    const int h = t[k] - t[k - 1];
    if (h < headway_min_s || h > headway_max_s)
      return "headway " + std::to_string(k) + " is " + std::to_string(h) + " s, outside [" +
             std::to_string(headway_min_s) + ", " + std::to_string(headway_max_s) + "] s";
  }
  return "";
}

}  // namespace ecorail::energy
