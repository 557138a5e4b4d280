// Reading per-second driving logs for calibration. Two formats are accepted (docs/calibration.md):
// the published per-second tables of the contest (time_hms, speed_cm_s, speed_kmh, accel_m_s2,
// distance_m, km_post_m, gradient_permille, traction_force_kN, traction_power_kW), and a plain
// CSV with named columns (time_s or time_hms; speed_kmh, speed_ms or speed_cm_s; optionally
// position_m, distance_m or km_post_m, gradient_permille, curve_radius_m, traction_force_kN,
// braking_force_kN, force_kN (signed) or notch). Everything is converted to SI on the way in; a
// missing column, a non-number, a negative speed or force and a time that does not increase are
// InputErrors naming file, row and field. Rows keep their file line for later reports.
#pragma once

#include <filesystem>
#include <iosfwd>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

namespace ecorail::fitting {

inline constexpr double kUnknown = std::numeric_limits<double>::quiet_NaN();

enum class LogFormat { Published, Plain };

struct LogRow {
  int source_row = 0;  // 1-based line in the file, the header being line 1
  double time_s = 0.0;
  double speed_ms = 0.0;
  double position_m = kUnknown;        // along the direction of travel; NaN when not logged
  double gradient_permille = 0.0;      // positive uphill in the direction of travel
  double curve_radius_m = 0.0;         // 0 = straight
  double traction_force_N = kUnknown;  // applied traction, >= 0; NaN when not known
  double braking_force_N = kUnknown;   // applied braking, >= 0; NaN when not known
  double notch = kUnknown;  // -1..1: fraction of the braking (<0) or traction (>0) envelope
};

struct Log {
  std::string label;  // file name, for messages
  LogFormat format = LogFormat::Plain;
  std::string speed_column = "speed_kmh";  // as spelt in the file, for messages
  std::vector<LogRow> rows;
  bool has_position = false;
  bool has_gradient = false;
  bool has_curve = false;
  bool has_traction = false;  // traction force known on every row
  bool has_braking = false;   // braking force known on every row
  bool has_notch = false;
};

// Reads a log file; see the header comment for the accepted columns.
Log read_log(const std::filesystem::path& path);
Log parse_log(std::string_view text, const std::string& label);
// Writes a log in the plain format (time_s, speed_kmh, position_m, gradient_permille,
// curve_radius_m, traction_force_kN, braking_force_kN); unknown values are left empty only
// where the column is absent, so the file reads back to the same log.
void write_log_csv(const Log& log, std::ostream& out);

std::string_view format_name(LogFormat f);

}  // namespace ecorail::fitting
