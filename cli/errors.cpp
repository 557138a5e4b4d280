#include "cli/errors.hpp"

#include <cstdio>
#include <exception>
#include <iostream>

#include "base/error.hpp"
#include "data/input_error.hpp"
#include "dp/time_target.hpp"
#include "policy/ladder.hpp"

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

// The flag a library error of a command-line value is reported on, when the error names none.
const char* flag_of(const Error& e) {
  if (const auto* ladder = dynamic_cast<const policy::LadderTimeError*>(&e)) {
    return ladder->offset_s() == 0.0 ? "--time" : "--lambda-ladder";
  }
  switch (e.kind()) {
    case ErrorKind::kRunningTime:
      return "--time";
    case ErrorKind::kResourceLimit:  // a grid too fine for this machine
      return "--ds/--dv";
    case ErrorKind::kDwell:
      return "--dwell";
    default:
      return "";
  }
}

// Every library error: its one-line message and exit code, by kind. Bad input of any kind exits
// 2; a fit that did not converge is a result that is not usable and exits 1.
int report(const Error& e) {
  const auto* std_error = dynamic_cast<const std::exception*>(&e);
  const std::string what = std_error ? std_error->what() : std::string(error_kind_name(e.kind()));
  switch (e.kind()) {
    case ErrorKind::kBadInput:
    case ErrorKind::kPolicyFormat:  // names the file it read
    case ErrorKind::kPolicyMismatch:
      return fail(2, what);
    case ErrorKind::kInvalidOptions:
      return fail(2, "invalid options: " + what);
    case ErrorKind::kRunningTime:
    case ErrorKind::kResourceLimit:
    case ErrorKind::kDwell: {
      const std::string field = e.context().field.empty() ? flag_of(e) : e.context().field;
      const auto* infeasible = dynamic_cast<const dp::InfeasibleTimeError*>(&e);
      const std::string expected = infeasible ? time_message(*infeasible) : what;
      return fail(2, data::InputError("command line", 0, field, expected).what());
    }
    case ErrorKind::kNotConverged:
      return fail(1, what);
  }
  return fail(1, what);
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
  } catch (const Error& e) {
    return report(e);
  } catch (const std::exception& e) {
    return fail(1, e.what());
  }
  return 0;
}

}  // namespace ecorail::cli
