// ecorail: energy-optimal train driving. See README.md for the commands.
#include "cli/commands.hpp"
#include "cli/errors.hpp"
#include "data/atomic_file.hpp"
#include "data/version.hpp"

// Waiting OpenMP threads yield their core unless OMP_WAIT_POLICY says otherwise; the program
// runs as it is, without re-executing itself (cli/wait_policy.hpp).
int main(int argc, char** argv) {
  // Every file a loader reads is an input no output of the run may replace (data/atomic_file.hpp).
  ecorail::data::set_register_files_read(true);
  CLI::App app{"ecorail: energy-optimal driving of metro trains"};
  app.require_subcommand(1);
  app.set_version_flag("--version", ecorail::data::version_string());
  ecorail::cli::add_solve_command(app);
  ecorail::cli::add_min_time_command(app);
  ecorail::cli::add_fit_envelope_command(app);
  ecorail::cli::add_calibrate_command(app);
  ecorail::cli::add_policy_command(app);
  ecorail::cli::add_frontier_command(app);
  ecorail::cli::add_timetable_command(app);
  ecorail::cli::add_delay_command(app);
  ecorail::cli::add_montecarlo_command(app);
  ecorail::cli::add_export_command(app);
  // Errors become one line and an exit code in one place (cli/errors.cpp).
  return ecorail::cli::run_reporting_errors(app, argc, argv);
}
