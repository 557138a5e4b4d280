#include "cli/errors.hpp"

#include <cstdio>
#include <exception>
#include <iostream>

#include "data/input_error.hpp"
#include "dp/journey_plan.hpp"
#include "dp/resource_estimate.hpp"
#include "dp/time_target.hpp"
#include "policy/advisor.hpp"
#include "policy/ladder.hpp"
#include "policy/policy_table.hpp"

namespace ecorail::cli {

namespace {

int fail(int code, const std::string& message) {
  std::cerr << "ecorail: error: " << message << "\n";
  return code;
}

// A running time the library refused, as a command-line error on the flag that asked for it.
std::string time_message(const dp::InfeasibleTimeError& e) {
  if (e.subject().empty()) return e.what();
  char text[400];
  std::snprintf(text, sizeof text, "at least the minimum running time of %.2f s for %s; got %.2f s",
                e.minimum_s(), e.subject().c_str(), e.requested_s());
  return text;
}

}  // namespace

int run_reporting_errors(CLI::App& app, int argc, char** argv) {
  // CLI11's own messages get the program's prefix and stay on one line.
  app.failure_message([](const CLI::App*, const CLI::Error& e) {
    return std::string("ecorail: error: ") + e.what() + " (see --help)\n";
  });
  // A first word that is no command and no flag: say which word, and list the commands.
  if (argc > 1 && argv[1][0] != '-') {
    bool known = false;
    std::string names;
    for (const CLI::App* sub : app.get_subcommands({})) {
      known |= sub->check_name(argv[1]);
      names += (names.empty() ? "" : ", ") + sub->get_name();
    }
    if (!known)
      return fail(2, "unknown command '" + std::string(argv[1]) + "'; commands: " + names);
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : 2;
  } catch (const data::InputError& e) {
    return fail(2, e.what());
  } catch (const InvalidOptionsError& e) {
    return fail(2, std::string("invalid options: ") + e.what());
  } catch (const policy::LadderTimeError& e) {
    const char* flag = e.offset_s() == 0.0 ? "--time" : "--lambda-ladder";
    return fail(2, data::InputError("command line", 0, flag, time_message(e)).what());
  } catch (const dp::InfeasibleTimeError& e) {
    return fail(2, data::InputError("command line", 0, "--time", time_message(e)).what());
  } catch (const dp::TimeRequestError& e) {  // too long a time, a proportional share too short
    return fail(2, data::InputError("command line", 0, "--time", e.what()).what());
  } catch (const dp::ResourceLimitError& e) {  // a grid too fine for this machine
    return fail(2, data::InputError("command line", 0, "--ds/--dv", e.what()).what());
  } catch (const dp::DwellError& e) {
    return fail(2, data::InputError("command line", 0, "--dwell", e.what()).what());
  } catch (const policy::PolicyFormatError& e) {
    return fail(2, e.what());  // names the file it read
  } catch (const policy::PolicyMismatchError& e) {
    return fail(2, e.what());
  } catch (const std::exception& e) {
    return fail(1, e.what());
  }
  return 0;
}

}  // namespace ecorail::cli
