#include "cli/errors.hpp"

#include <charconv>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <iostream>

#include "base/error.hpp"
#include "data/input_error.hpp"
#include "dp/time_target.hpp"
#include "policy/ladder.hpp"
#include "recovery/delay_recovery.hpp"

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

// A whole decimal number, optionally signed, within [lowest, highest]; CLI11's conversion then
// reads the same value.
std::string integer_problem(const std::string& text, bool is_unsigned) {
  std::string digits = text;
  if (!digits.empty() && digits.front() == '+') digits.erase(0, 1);
  const bool negative = !digits.empty() && digits.front() == '-';
  const std::string magnitude = negative ? digits.substr(1) : digits;
  const bool all_digits =
      !magnitude.empty() && magnitude.find_first_not_of("0123456789") == std::string::npos;
  const std::string range = is_unsigned ? "from 0 to 18446744073709551615"
                                        : "from -9223372036854775808 to 9223372036854775807";
  if (!all_digits || (negative && is_unsigned)) {
    return "a whole decimal number " + range + "; got '" + text + "'";
  }
  bool fits = false;
  if (is_unsigned) {
    std::uint64_t v = 0;
    const auto [end, ec] =
        std::from_chars(magnitude.data(), magnitude.data() + magnitude.size(), v);
    fits = ec == std::errc() && end == magnitude.data() + magnitude.size();
  } else {
    std::int64_t v = 0;
    const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), v);
    fits = ec == std::errc() && end == digits.data() + digits.size();
  }
  return fits ? "" : "a whole number " + range + "; got '" + text + "'";
}

// The same number without leading zeros (CLI11 would read 010 as octal).
std::string decimal(const std::string& text) {
  std::string sign, digits = text;
  if (!digits.empty() && (digits.front() == '+' || digits.front() == '-')) {
    if (digits.front() == '-') sign = "-";
    digits.erase(0, 1);
  }
  const auto first = digits.find_first_not_of('0');
  digits = first == std::string::npos ? "0" : digits.substr(first);
  return digits == "0" ? digits : sign + digits;
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
  if (const auto* rung = dynamic_cast<const policy::LadderRungError*>(&e)) {
    // A ladder rung the engine cannot solve: the nominal time (--time) or an offset.
    if (rung->offset_s() == 0.0)
      return fail(2, data::InputError("command line", 0, "--time", what).what());
    return fail(2, data::InputError("command line", 0, "--lambda-ladder",
                                    "offsets whose running times the engine solves; " + what)
                       .what());
  }
  if (const auto* delay = dynamic_cast<const recovery::DelayInputError*>(&e)) {
    // The argument of `delay` it names: the plan (its file, or the reference plan) or a flag.
    const std::string& field = delay->field();
    const bool file = field == "plan" && !delay->context().file.empty();
    return fail(2, data::InputError(
                       file ? delay->context().file : "command line", 0,
                       field == "plan" ? (file ? "--plan" : "--reference") : "--" + field, what)
                       .what());
  }
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

void bad(const std::string& flag, const std::string& expected) {
  throw data::InputError("command line", 0, flag, expected);
}

void throw_on_flag(const std::string& why, std::initializer_list<FieldFlag> flags) {
  for (const FieldFlag& f : flags) {
    const std::string field = f.field;
    if (why.rfind(field, 0) != 0) continue;
    std::string rest = why.substr(field.size());
    for (const char* lead : {": expected ", ": ", " must be ", " must "}) {
      if (rest.rfind(lead, 0) == 0) {
        rest.erase(0, std::string(lead).size());
        break;
      }
    }
    // "must be in (0, 100] m" reads "expected a value in (0, 100] m".
    if (rest.rfind("in ", 0) == 0) rest = "a value " + rest;
    throw data::InputError("command line", 0, f.flag, rest);
  }
  throw InvalidOptionsError(why);
}

void throw_on_known_flag(const std::string& why) {
  throw_on_flag(why, {{"grid ds_m", "--ds"},
                      {"grid dv_kmh", "--dv"},
                      {"threads", "--threads"},
                      {"objective", "--objective"},
                      {"t_min_s", "--tmin"},
                      {"t_max_s", "--tmax"},
                      {"step_s", "--step"},
                      {"min_length_m", "--min-regime-m"},
                      {"min_duration_s", "--min-regime-s"},
                      {"split", "--split"}});
}

void parse_integers_strictly(CLI::App& app) {
  for (CLI::Option* option : app.get_options()) {
    const std::string type = option->get_type_name();
    if (type != "INT" && type != "UINT") continue;
    const bool is_unsigned = type == "UINT";
    option->transform(CLI::Validator(
        [is_unsigned](std::string& text) {
          const std::string problem = integer_problem(text, is_unsigned);
          if (!problem.empty()) return "expected " + problem;
          text = decimal(text);
          return std::string();
        },
        "", ""));
  }
  for (CLI::App* sub : app.get_subcommands({})) parse_integers_strictly(*sub);
}

int run_reporting_errors(CLI::App& app, int argc, char** argv) {
  parse_integers_strictly(app);
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
