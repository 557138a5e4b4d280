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

// Checks a library options struct before any work (exit 2 with its message).
template <typename Options>
void require_valid(const Options& options) {
  std::string why;
  if (!options.IsValid(&why)) throw InvalidOptionsError(why);
}

// Parses the command line and runs the chosen command; prints any error as one line and
// returns the exit code (0 on success).
int run_reporting_errors(CLI::App& app, int argc, char** argv);

}  // namespace ecorail::cli
