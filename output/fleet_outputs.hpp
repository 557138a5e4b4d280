// Outputs of the fleet timetable commands: the timetable (train, station, arrival, departure)
// as CSV and XLSX, the energy breakdown as JSON, the train diagram (time-distance lines of all
// trains, SVG or PNG by gnuplot) and the power plot (total traction, regenerated, used and
// substation power over a time window). The writers take what the timetable room computed and
// format it; they compute nothing.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <ostream>
#include <string>
#include <vector>

#include "output/gnuplot.hpp"
#include "physics/trip.hpp"
#include "timetable/fleet_models.hpp"
#include "timetable/power_balance.hpp"

namespace ecorail::output {

// Every train's stops on the clock: the pattern trip shifted to each departure.
struct FleetTimetable {
  std::vector<std::string> stations;  // in the order of travel
  std::vector<double> positions_m;    // along the run
  std::vector<int> departures_s;
  physics::Trip trip;  // the pattern, departing at 0
};

// "HH:MM:SS" of a clock time in seconds past the service day's start (rounded to the second).
std::string clock_text(double t_s);

void write_timetable_csv(std::ostream& out, const FleetTimetable& timetable);
// Writes the workbook to file (a temporary the caller renames): sheet "timetable" with the
// rows of the CSV, numbers as numbers, header frozen.
void write_timetable_xlsx(const std::filesystem::path& file, const FleetTimetable& timetable,
                          const nlohmann::json& energy);

// The energy breakdown (keys in docs/fleet.md).
nlohmann::json fleet_energy_json(const timetable::FleetEvaluation& evaluation,
                                 const timetable::FleetProblem& problem);

// Plots into file in the given format (a temporary's name says nothing: the caller takes the
// format from the target's name, plot_format_for). window: [from_s, to_s) of the clock.
void write_train_diagram(const std::filesystem::path& file, PlotFormat format,
                         const FleetTimetable& timetable, double from_s, double to_s,
                         const std::string& title);
void write_power_plot(const std::filesystem::path& file, PlotFormat format,
                      const timetable::PowerBalance::Trace& trace, const std::string& title);

}  // namespace ecorail::output
