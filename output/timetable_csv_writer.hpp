// The timetable CSV, one layout for every writer (docs/formats.md, "Timetable CSV"): one row per
// train and station, columns train (1-based), station, position_m (along the run from the first
// station), arrival_s and departure_s (clock seconds), arrival and departure (HH:MM:SS) and
// dwell_s. `ecorail timetable evaluate|optimise --csv` writes it from a fleet timetable
// (output/fleet_outputs.hpp), `ecorail montecarlo --adjust --adjusted-csv` from a delay plan;
// `ecorail delay|montecarlo --plan` read it back (data/timetable_csv_reader.hpp).
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "recovery/plan.hpp"

namespace ecorail::output {

struct TimetableCsvRow {
  std::size_t train = 0;  // 1-based
  std::string station;
  double position_m = 0.0, arrival_s = 0.0, departure_s = 0.0, dwell_s = 0.0;
};

// "HH:MM:SS" of a clock time in seconds past the service day's start (rounded to the second).
std::string clock_text(double t_s);

void write_timetable_csv(std::ostream& out, const std::vector<TimetableCsvRow>& rows);
// A delay plan's rows; positions_m: each station's position along the run (as many as the
// plan's stations).
void write_timetable_csv(std::ostream& out, const recovery::Plan& plan,
                         const std::vector<double>& positions_m);

}  // namespace ecorail::output
