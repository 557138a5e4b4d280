// Reading a timetable plan for the delay commands (`ecorail delay`, `ecorail montecarlo`): the
// timetable CSV that `ecorail timetable evaluate|optimise --csv` writes (columns train,
// station, arrival_s, departure_s; others ignored), rows grouped by train, stations in the order
// of their rows; or the 2.1 reference plan. Bad files are data::InputError naming file, row and
// field.
#pragma once

#include <string>
#include <vector>

#include "data/line.hpp"
#include "recovery/plan.hpp"

namespace ecorail::cli {

recovery::Plan read_plan(const std::string& file);
// InputError unless the plan's stations are every station of the line between its first and
// last, in the order of travel.
void check_plan_stations(const data::Line& line, const recovery::Plan& plan,
                         const std::string& file);

}  // namespace ecorail::cli
