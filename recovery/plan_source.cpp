#include "recovery/plan_source.hpp"

#include <cstdio>

#include "data/input_error.hpp"
#include "data/route_builder.hpp"
#include "data/timetable_csv_reader.hpp"
#include "data/train_io.hpp"

namespace ecorail::recovery {

Plan read_plan_csv(const std::string& file) {
  data::TimetableStopTimes table = data::read_timetable_csv(file);
  Plan plan;
  plan.stations = std::move(table.stations);
  for (std::size_t k = 0; k < table.arrival_s.size(); ++k)
    plan.trains.push_back({std::move(table.arrival_s[k]), std::move(table.departure_s[k])});
  if (const std::string why = plan.problem(); !why.empty())
    throw data::InputError(file, 0, "arrival_s/departure_s", "a timetable that holds: " + why);
  return plan;
}

void check_plan_stations(const data::Line& line, const Plan& plan, const std::string& file) {
  const std::vector<std::string>& stops = plan.stations;
  std::vector<std::string> line_stops;
  try {
    line_stops = data::stops_between(line, stops.front(), stops.back());
  } catch (const data::InputError&) {
    throw data::InputError(file, 0, "station",
                           "stations of the line; got " + stops.front() + " .. " + stops.back());
  }
  if (line_stops != stops)
    throw data::InputError(file, 0, "station",
                           "every station of the line between " + stops.front() + " and " +
                               stops.back() + ", in the order of travel");
}

PlanStops read_plan_stops(const data::Line& line, const std::string& plan_file) {
  PlanStops out;
  if (plan_file.empty()) {
    out.stops = data::stops_between(line, line.stations.front().name, line.stations.back().name);
    return out;
  }
  out.plan = read_plan_csv(plan_file);
  out.stops = out.plan.stations;
  check_plan_stations(line, out.plan, plan_file);
  return out;
}

std::unique_ptr<dp::SectionLibrary> plan_section_library(const data::Line& line,
                                                         const physics::Train& train,
                                                         const std::vector<std::string>& stops,
                                                         const dp::SectionLibraryOptions& options) {
  char key[200];
  std::snprintf(key, sizeof key, "delay|%016llx|%016llx|%s",
                static_cast<unsigned long long>(line.checksum()),
                static_cast<unsigned long long>(data::train_checksum(train)),
                line.curve_formula == data::CurveFormula::Roeckl ? "roeckl" : "600/R");
  return std::make_unique<dp::SectionLibrary>(train, data::build_routes(line, stops, train),
                                              options, key);
}

Plan reference_plan_on(const dp::SectionLibrary& library, const std::vector<std::string>& stops) {
  dp::JourneyOptions journey;
  journey.engine = library.options().engine;
  journey.measure_marginals = false;
  return reference_plan(library, stops, journey);
}

}  // namespace ecorail::recovery
