// Preparing logs for the fits: converts rows to the model's inputs (speed, applied traction and
// braking force, track resistance), decides which one-second intervals between consecutive rows
// the equation of motion can explain, and checks positions against speeds. An interval is used
// only when the force is known at both ends and stays in one regime (traction, coast, braking)
// without a step, the train moves at both ends and the gap is short; every other interval is
// excluded with its reason, because inside it the force is unknown and a fit would read the
// switch as resistance. Logs without a braking column (the published tables) count a zero-force
// row as braking with unknown force when it decelerates much faster than coasting could.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "fitting/log_reader.hpp"
#include "physics/train.hpp"

namespace ecorail::fitting {

struct PrepOptions {
  double max_gap_s = 5.0;                 // longer gaps between rows are not bridged
  double standing_speed_kmh = 0.5;        // an interval touching a slower row is a stop or start
  double force_step_fraction = 0.25;      // a larger relative force change is a control switch
  double force_step_min_kN = 5.0;         // ... when also larger than this
  double brake_detect_margin_m_s2 = 0.2;  // unknown-brake logs: decel beyond coasting + this
  double zero_force_kN = 0.5;             // below this a logged force counts as zero
};

enum class Regime { Traction, Coast, Braking, Unknown };

struct PreparedRow {
  int log_index = 0;
  int source_row = 0;
  double time_s = 0.0;
  double speed_ms = 0.0;
  double traction_N = 0.0;
  double braking_N = 0.0;
  double gradient_permille = 0.0;
  double curve_N_per_kN = 0.0;  // 600 / R
  double position_m = kUnknown;
  Regime regime = Regime::Unknown;
};

enum class IntervalStatus {
  Used,
  Gap,           // rows too far apart in time
  Standing,      // the train stands at one end
  UnknownForce,  // force not known at one end
  Switch,        // regime change between the rows
  ForceStep,     // force jumps between the rows
};
inline constexpr int kIntervalStatusCount = 6;
std::string_view interval_status_name(IntervalStatus s);

struct PositionInconsistency {
  int log_index = 0;
  int row_from = 0;  // source rows
  int row_to = 0;
  double logged_m = 0.0;    // distance advanced according to the position column
  double expected_m = 0.0;  // distance the logged speeds cover (trapezoid)
  int suspect_row = 0;      // the row whose position is out of line, when one explains it
};

struct PreparedLog {
  std::string label;
  std::vector<PreparedRow> rows;
  std::vector<IntervalStatus> intervals;  // intervals[i] joins rows[i] and rows[i+1]
};

struct PreparedData {
  std::vector<PreparedLog> logs;
  std::vector<PositionInconsistency> position_issues;
  int rows = 0;
  int used_intervals = 0;
  int status_counts[kIntervalStatusCount] = {};
  int inferred_braking_rows = 0;                    // rows taken as braking with unknown force
  double min_speed_kmh = 0.0, max_speed_kmh = 0.0;  // over rows of used intervals
  double min_gradient_permille = 0.0, max_gradient_permille = 0.0;
  int gradient_intervals = 0;  // used intervals with |gradient| >= 0.5 per mille
  int force_intervals = 0;     // used intervals with traction or braking force
  int braking_intervals = 0;   // used intervals with braking force
};

// Converts and classifies; base supplies the envelopes for notch columns and the coasting
// deceleration for brake detection.
PreparedData prepare_logs(const std::vector<Log>& logs, const physics::Train& base,
                          const PrepOptions& options);

}  // namespace ecorail::fitting
