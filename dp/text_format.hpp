// The solvers' text: format_text (printf into a std::string, base/format_text.hpp, re-exported
// here), the time price as text and the result block of the full reports.
#pragma once

#include <string>
#include <vector>

#include "base/format_text.hpp"
#include "dp/termination.hpp"

namespace ecorail::dp {

using ecorail::format_text;

// The time price lambda as every text output writes it (reports, tables): kJ/s with three
// decimals, e.g. "264.359 kJ/s". JSON and CSV carry the same number under "lambda" (with
// "lambda_unit": "kJ/s") or a column "lambda_kJ_per_s".
inline std::string lambda_text(double lambda_J_per_s) {
  return format_text("%.3f kJ/s", lambda_J_per_s / 1000.0);
}

// The "Re-simulated result" block that ends a section's or a journey's full report, so both
// name and format the same figures alike (stop_label: "Stop error", "Stop error (largest)").
struct ResultBlock {
  double running_time_s, traction_energy_kJ, braking_energy_kJ, regen_energy_kJ, net_energy_kJ;
  const char* stop_label;
  double stop_error_m, max_overspeed_kmh;
  Termination termination;
  const std::vector<std::string>* warnings;
};
inline std::string result_block_text(const ResultBlock& b) {
  std::string r = "\n  Re-simulated result\n";
  r += format_text("  %-28s %.4f s\n", "Running time", b.running_time_s);
  r += format_text("  %-28s %.3f kJ\n", "Traction energy", b.traction_energy_kJ);
  r += format_text("  %-28s %.3f kJ\n", "Braking work", b.braking_energy_kJ);
  r += format_text("  %-28s %.3f kJ\n", "Regenerated energy", b.regen_energy_kJ);
  r += format_text("  %-28s %.3f kJ\n", "Net energy", b.net_energy_kJ);
  r += format_text("  %-28s %.4f m\n", b.stop_label, b.stop_error_m);
  r += format_text("  %-28s %.4f km/h\n", "Max overspeed", b.max_overspeed_kmh);
  r += format_text("\n  %-28s %s\n", "Termination",
                   std::string(termination_name(b.termination)).c_str());
  if (b.warnings != nullptr)
    for (const auto& w : *b.warnings) r += "  warning: " + w + "\n";
  return r;
}

}  // namespace ecorail::dp
