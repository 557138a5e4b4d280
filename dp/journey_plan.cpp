#include "dp/journey_plan.hpp"

#include <cmath>

namespace ecorail::dp {

namespace {

std::string intermediate_list(const std::vector<std::string>& stops) {
  std::string list;
  for (std::size_t i = 1; i + 1 < stops.size(); ++i) list += (list.empty() ? "" : ", ") + stops[i];
  return list;
}

void check_seconds(double dwell_s, const std::string& what) {
  if (!(std::isfinite(dwell_s) && dwell_s >= 0.0)) {
    throw DwellError("a dwell in seconds >= 0 for " + what);
  }
}

}  // namespace

std::vector<double> resolve_dwells(const DwellSpec& spec, const std::vector<std::string>& stops) {
  if (spec.every_stop_s) check_seconds(*spec.every_stop_s, "every stop");
  for (const auto& [station, dwell_s] : spec.by_stop_s) {
    bool intermediate = false;
    for (std::size_t i = 1; i + 1 < stops.size(); ++i) intermediate |= stops[i] == station;
    if (!intermediate) {
      throw DwellError("an intermediate stop of this run (" + intermediate_list(stops) +
                       "); got '" + station + "'");
    }
    check_seconds(dwell_s, station);
  }
  std::vector<double> dwells;
  for (std::size_t i = 1; i + 1 < stops.size(); ++i) {
    std::optional<double> dwell = spec.every_stop_s;
    for (const auto& [station, dwell_s] : spec.by_stop_s) {
      if (station == stops[i]) dwell = dwell_s;  // the last one named wins
    }
    if (!dwell) {
      throw DwellError("a dwell for the intermediate stop " + stops[i] +
                       " (one for this stop, or one for every stop)");
    }
    dwells.push_back(*dwell);
  }
  return dwells;
}

}  // namespace ecorail::dp
