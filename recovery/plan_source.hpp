// Where the delay studies (`ecorail delay`, `ecorail montecarlo`, ecorail.delay.recover and
// ecorail.montecarlo) get their plan and its section library: a timetable CSV read and checked
// against the line (data/timetable_csv_reader.hpp; a bad file fails before any engine is built), or
// the 2.1 reference plan made on the library of the whole line. The library of a plan's stations is
// keyed for the frontier cache by line, train and curve formula, the same key for every delay
// study, so they share cached frontiers.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "data/line.hpp"
#include "dp/section_library.hpp"
#include "physics/train.hpp"
#include "recovery/plan.hpp"

namespace ecorail::recovery {

// The plan of a timetable CSV: data::InputError naming the file, row and field when it does not
// hold (times falling along a train, trains out of departure order).
Plan read_plan_csv(const std::string& file);
// data::InputError (file, field "station") unless the plan's stations are every station of the
// line between its first and last, in the order of travel.
void check_plan_stations(const data::Line& line, const Plan& plan, const std::string& file);
// The stations a plan runs over: those of plan_file (read, checked against the line), or with
// plan_file empty every station of the line (the reference plan's, made later on the library
// by reference_plan_on). plan is left empty for the reference.
struct PlanStops {
  Plan plan;
  std::vector<std::string> stops;
};
PlanStops read_plan_stops(const data::Line& line, const std::string& plan_file);

// The section library of stops with options (its grid and frontier span), keyed for the
// frontier cache.
std::unique_ptr<dp::SectionLibrary> plan_section_library(const data::Line& line,
                                                         const physics::Train& train,
                                                         const std::vector<std::string>& stops,
                                                         const dp::SectionLibraryOptions& options);
// The 2.1 reference plan made on that library (docs/delays.md).
Plan reference_plan_on(const dp::SectionLibrary& library, const std::vector<std::string>& stops);

}  // namespace ecorail::recovery
