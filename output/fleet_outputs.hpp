// Outputs of the fleet timetable commands: the timetable (train, station, arrival, departure)
// as CSV and XLSX, the energy breakdown as JSON, the train diagram (time-distance lines of all
// trains, SVG or PNG by gnuplot) and the power plot (total traction, regenerated, used and
// substation power over a time window). The writers take what fleet/ and energy/ computed and
// format it; they compute nothing.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <ostream>
#include <string>
#include <vector>

#include "energy/fleet_energy_model.hpp"
#include "energy/power_flow_balance.hpp"
#include "fleet/fleet_problem.hpp"
#include "output/gnuplot.hpp"
#include "output/timetable_csv_writer.hpp"
#include "physics/trip.hpp"
#include "power/load_flow.hpp"
#include "power/network_evaluation.hpp"

namespace ecorail::output {

// Every train's stops on the clock: the pattern trip shifted to each departure.
struct FleetTimetable {
  std::vector<std::string> stations;  // in the order of travel
  std::vector<double> positions_m;    // along the run
  std::vector<int> departures_s;
  physics::Trip trip;                           // the pattern, departing at 0
  std::vector<fleet::PeakWindow> peak_windows;  // shaded on the train diagram
  // Per-train patterns: train k's own trip (departing at 0); empty when all run `trip`.
  std::vector<physics::Trip> per_train_trips;
  // Train k's run on the clock.
  physics::Trip train_trip(std::size_t k) const {
    return (per_train_trips.empty() ? trip : per_train_trips.at(k)).shifted(departures_s.at(k));
  }
};

// The timetable CSV (output/timetable_csv_writer.hpp) of every train's stops.
void write_timetable_csv(std::ostream& out, const FleetTimetable& timetable);
// Writes the workbook to file (a temporary the caller renames): sheet "timetable" with the
// rows of the CSV, numbers as numbers, header frozen.
void write_timetable_xlsx(const std::filesystem::path& file, const FleetTimetable& timetable,
                          const nlohmann::json& energy);

// The energy breakdown (keys in docs/fleet.md).
nlohmann::json fleet_energy_json(const energy::FleetEvaluation& evaluation,
                                 const fleet::FleetProblem& problem);

// Plots into file in the given format (a temporary's name says nothing: the caller takes the
// format from the target's name, plot_format_for). window: [from_s, to_s) of the clock.
void write_train_diagram(const std::filesystem::path& file, PlotFormat format,
                         const FleetTimetable& timetable, double from_s, double to_s,
                         const std::string& title);
void write_power_plot(const std::filesystem::path& file, PlotFormat format,
                      const energy::PowerBalance::Trace& trace, const std::string& title);

// Network model: the keys of docs/fleet.md's network section (substations, line losses,
// traction input, auxiliaries, used and curtailed regeneration, train voltages, curtailment
// events), added to the energy breakdown.
void add_network_json(nlohmann::json& energy, const power::NetworkEvaluation& network);
// Power of every substation over the trace's window.
void write_substation_plot(const std::filesystem::path& file, PlotFormat format,
                           const power::SubstationTrace& trace, const std::string& title);
// The voltage along the line at one instant: the load flow's nodes (substations and trains,
// joined by the conductor's linear voltage drop), with the trains' voltage limits.
void write_voltage_plot(const std::filesystem::path& file, PlotFormat format,
                        const power::LoadFlowResult& flow, const power::PowerSupply& supply,
                        const std::vector<int>& train_numbers, const std::string& title);

}  // namespace ecorail::output
