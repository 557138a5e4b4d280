#include <string>

#include "dp/text_format.hpp"
#include "dp/timing_journey.hpp"

namespace ecorail::dp {

bool TimingJourneyOptions::IsValid(std::string* error) const {
  auto fail = [&](const char* why) {
    if (error) *error = why;
    return false;
  };
  if (!engine.IsValid(error)) return false;
  if (!(time_tolerance_s > 0.0 && time_tolerance_s <= 1.0)) {
    return fail("time_tolerance_s must be in (0, 1] s");
  }
  if (!(speed_tolerance_kmh > 0.0 && speed_tolerance_kmh <= 5.0)) {
    return fail("speed_tolerance_kmh must be in (0, 5] km/h");
  }
  if (max_evaluations < 10) return fail("max_evaluations must be at least 10");
  return true;
}

std::string TimingJourneySummary::BriefReport() const {
  return format_text(
      "ecorail solve --journey %s (%d parts, %.1f m) in %.3f s running time (trip %.3f s): "
      "traction %.1f kJ, regenerated %.1f kJ, windows %s; %d price evaluations, %.3f s wall, "
      "%s\n",
      id.empty() ? "-" : id.c_str(), parts, distance_m, running_time_s, trip_time_s,
      traction_energy_kJ, regen_energy_kJ, windows_met ? "met" : "MISSED", evaluations,
      total_wall_s, std::string(status_word(termination, warnings.size())).c_str());
}

std::string TimingJourneySummary::FullReport() const {
  std::string r = "Timing-point journey " + (id.empty() ? std::string("-") : id) + "\n";
  r += format_text("  %-28s %d\n", "Parts (stop to stop)", parts);
  r += format_text("  %-28s %.1f m\n", "Distance", distance_m);
  r += format_text("  %-28s ds %.3f m, dv %.3f km/h\n", "Grid", grid.ds_m, grid.dv_kmh);
  r += format_text("  %-28s %s\n", "Objective", std::string(objective_name(objective)).c_str());
  r += format_text("  %-28s %d\n", "Price evaluations", evaluations);
  r += format_text("  %-28s %.3f s\n", "Wall time", total_wall_s);
  r += format_text("  %-28s %.4f s\n", "Running time", running_time_s);
  r += format_text("  %-28s %.4f s\n", "Trip time", trip_time_s);
  r += format_text("  %-28s %.3f kJ\n", "Traction energy", traction_energy_kJ);
  r += format_text("  %-28s %.3f kJ\n", "Regenerated energy", regen_energy_kJ);
  r += format_text("  %-28s %.3f kJ\n", "Net energy", net_energy_kJ);
  r += format_text("  %-28s %s\n", "Windows met", windows_met ? "yes" : "no");
  r += format_text("  %-28s %s\n", "Termination",
                   std::string(termination_name(termination)).c_str());
  for (const auto& w : warnings) r += "  warning: " + w + "\n";
  return r;
}

}  // namespace ecorail::dp
