// Flags of `ecorail timetable evaluate|optimise` and their parsing into the fleet problem, the
// energy model's options and the departures; the command itself is cli/cmd_timetable.cpp.
#pragma once

#include <CLI/CLI.hpp>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "cli/errors.hpp"
#include "cli/output_options.hpp"
#include "cli/problem_options.hpp"
#include "cli/service_options.hpp"
#include "energy/model_options.hpp"
#include "fleet/fleet_problem.hpp"
#include "fleet/timetable_study.hpp"

namespace ecorail::cli {

struct TimetableArgs {
  ProblemOptions problem;
  int trains = 100;
  int span_s = 63900;
  std::string headway = "120:660";
  double trip_time_s = 2086.0;
  std::string dwell_range = "30:45";
  double dwell_s = 30.0;
  std::string model = "power-flow";
  std::string overlap = "ahead";
  double step_s = 0.01;
  std::vector<double> sections_at_m;
  std::string headways_file, departures_file;
  bool uniform = false;
  // optimise: --seed, --time-limit, --gap, --restarts, --moves, --rounds, --anneal-step and
  // --per-train-patterns set these fields (and take their defaults from them); --optimise and
  // --threads complete them.
  fleet::StudyOptimiseOptions search;
  std::string optimise = "headways";
  bool optimise_given = false;  // --optimise on the command line (not its default)
  std::string json, csv, xlsx, diagram, power_plot;
  std::string window = "0:7200";
  std::vector<std::string> peaks;             // --peak FROM:TO, any number
  std::string peak_headway, offpeak_headway;  // "" : 120:150 and 300:660 with --peak
  std::string nearest;                        // evaluate --nearest PEAK:OFFPEAK
  bool quiet = false;
  bool full_report = false;
  ServiceArgs service;  // --separation, --profiles, ... (cli/service_options.hpp)
  // Network model (docs/power_network.md).
  std::string power_supply, voltage_plot;
  double voltage_at_s = 3600.0;
  CLI::Option* overlap_option = nullptr;        // whether --overlap was given
  CLI::Option* service_train_length = nullptr;  // whether --train-length was given
  CLI::Option* service_separation = nullptr;    // --separation's raw values
  CLI::Option* step_option = nullptr;  // whether --step was given (the network's default differs)
  OutputOptions gtfs;                  // --gtfs DIR, --gtfs-start (its other fields unused)
};

// "A:B" as two numbers, A <= B.
std::pair<double, double> parse_range(const std::string& text, const std::string& flag);
fleet::FleetProblem fleet_problem(const TimetableArgs& a);
// The model's options; refuses flags the chosen model does not use.
energy::EnergyModelOptions model_options(const TimetableArgs& a);
// Departures from --headways FILE, --departures FILE, --nearest or uniform.
std::vector<int> read_departures(const TimetableArgs& a, const fleet::FleetProblem& p);
void add_fleet_options(CLI::App* cmd, TimetableArgs& a);
// Checks the outputs and the flags, loads the line and train, and builds the study (section
// library, pattern, model); a trip time or option that does not fit the run is an InputError.
fleet::TimetableStudy make_study(const TimetableArgs& a);

}  // namespace ecorail::cli
