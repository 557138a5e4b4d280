// Subcommands of the ecorail program. Each lives in its own cli/cmd_*.cpp and registers itself
// on the CLI11 app; cli/errors.cpp turns exceptions into one-line errors and exit codes.
#pragma once

#include <CLI/CLI.hpp>

namespace ecorail::cli {

void add_solve_command(CLI::App& app);
void add_min_time_command(CLI::App& app);
void add_fit_envelope_command(CLI::App& app);
void add_calibrate_command(CLI::App& app);
void add_policy_command(CLI::App& app);
void add_frontier_command(CLI::App& app);
// `ecorail timetable evaluate|optimise`: fleet timetables (cli/cmd_timetable.cpp).
void add_timetable_command(CLI::App& app);
// `ecorail delay`: recovery of one late departure (cli/cmd_delay.cpp, docs/delays.md).
void add_delay_command(CLI::App& app);
// `ecorail montecarlo`: service days under random delays (cli/cmd_montecarlo.cpp).
void add_montecarlo_command(CLI::App& app);
// `ecorail export`: the line and train as TTOBench JSON (cli/cmd_export.cpp).
void add_export_command(CLI::App& app);

}  // namespace ecorail::cli
