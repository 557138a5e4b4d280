// Errors of the ecorail program in one place: which library error (an ecorail::Error, by its
// kind) becomes which one-line message and exit code. Bad input of any kind (a malformed flag, an
// options struct that fails its IsValid, a running time outside what the section allows, an
// unreadable policy table, a bad line or train file) exits 2; anything else (a solve that is not
// usable, an I/O failure) exits 1. Every message is one line on stderr starting "ecorail: error: ".
#pragma once

#include <CLI/CLI.hpp>
#include <stdexcept>
#include <string>

#include "base/error.hpp"

namespace ecorail::cli {

// An options struct of the library refused by its IsValid; the message names the field.
class InvalidOptionsError : public std::invalid_argument, public Error {
 public:
  explicit InvalidOptionsError(const std::string& what)
      : std::invalid_argument(what), Error(ErrorKind::kInvalidOptions) {}
};

// An IsValid message on the flag that sets the field it names, for the fields the shared flags
// set (--ds, --dv, --threads, --objective, --tmin, --tmax, --step, --min-regime-m,
// --min-regime-s, --split); InvalidOptionsError with the message otherwise.
[[noreturn]] void throw_on_known_flag(const std::string& why);

// A flag's value refused before any work: "command line: field '<flag>': expected <expected>"
// (exit 2).
[[noreturn]] void bad(const std::string& flag, const std::string& expected);

// Checks a library options struct before any work (exit 2): a field a flag of the program sets
// is reported on that flag (throw_on_known_flag), any other as its message says.
template <typename Options>
void require_valid(const Options& options) {
  std::string why;
  if (!options.IsValid(&why)) throw_on_known_flag(why);
}

// Which command-line flag sets which field of a library options struct.
struct FieldFlag {
  const char* field;  // as IsValid names it, e.g. "braking_m_s2"
  const char* flag;   // e.g. "--braking"
};

// An IsValid message ("field: expected ..." or "field must ...") as the InputError of the one
// flag that set the field (exit 2): "command line: field '--braking': expected 0 (the train's)
// to 10 m/s^2". A field none of flags sets is reported as the message says.
[[noreturn]] void throw_on_flag(const std::string& why, std::initializer_list<FieldFlag> flags);

// Checks options like require_valid, naming the flag of the field at fault (throw_on_flag).
template <typename Options>
void require_valid_flags(const Options& options, std::initializer_list<FieldFlag> flags) {
  std::string why;
  if (!options.IsValid(&why)) throw_on_flag(why, flags);
}

// Every integer option of app and its subcommands reads a whole decimal number within its type
// or is refused (exit 2): CLI11 alone would read 2^64 as 2^64 - 1, -1 as 2^64 - 1 for an
// unsigned option, and 010 as octal 8.
void parse_integers_strictly(CLI::App& app);

// Parses the command line and runs the chosen command; prints any error as one line and
// returns the exit code (0 on success).
int run_reporting_errors(CLI::App& app, int argc, char** argv);

}  // namespace ecorail::cli
