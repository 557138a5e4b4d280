// ecorail: energy-optimal train driving. See README.md for the commands.
#include <cstdio>
#include <exception>
#include <iostream>

#include "cli/commands.hpp"
#include "data/input_error.hpp"

int main(int argc, char** argv) {
  CLI::App app{"ecorail: energy-optimal driving of metro trains"};
  app.require_subcommand(1);
  ecorail::cli::add_solve_command(app);
  ecorail::cli::add_min_time_command(app);
  ecorail::cli::add_fit_envelope_command(app);
  ecorail::cli::add_calibrate_command(app);
  ecorail::cli::add_policy_command(app);
  ecorail::cli::add_frontier_command(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : 2;
  } catch (const ecorail::data::InputError& e) {
    std::cerr << "ecorail: error: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "ecorail: error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
