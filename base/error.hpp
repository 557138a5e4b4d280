// ecorail::Error: what every error a user can cause carries, whichever room throws it. A kind
// (what went wrong, so the program maps it to its exit code in one place, cli/errors.cpp) and a
// context (the file, the 1-based row with the header as row 1 or 0, and the field or flag; any
// may be empty). Each library error type derives from its standard exception (what() is the
// one-line message) and from Error, so `catch (const ecorail::Error&)` sees them all and
// `catch (const std::invalid_argument&)` still sees the ones that are bad arguments.
#pragma once

#include <string>
#include <string_view>
#include <utility>

namespace ecorail {

enum class ErrorKind {
  kBadInput,        // a file or flag does not say what it must (data::InputError)
  kInvalidOptions,  // an options struct refused by its IsValid
  kRunningTime,     // a running time no run can meet, or beyond what is solved reliably
  kDwell,           // a dwell plan that does not fit the stops
  kResourceLimit,   // a problem too large for this machine
  kPolicyFormat,    // a policy table file that is not one
  kPolicyMismatch,  // a policy table built for another line, train or grid
  kNotConverged,    // a fit or search that did not reach its target
};

// One name per kind: "bad input", "invalid options", ...
inline std::string_view error_kind_name(ErrorKind kind) {
  switch (kind) {
    case ErrorKind::kBadInput:
      return "bad input";
    case ErrorKind::kInvalidOptions:
      return "invalid options";
    case ErrorKind::kRunningTime:
      return "running time";
    case ErrorKind::kDwell:
      return "dwell";
    case ErrorKind::kResourceLimit:
      return "resource limit";
    case ErrorKind::kPolicyFormat:
      return "policy format";
    case ErrorKind::kPolicyMismatch:
      return "policy mismatch";
    case ErrorKind::kNotConverged:
      return "not converged";
  }
  return "error";
}

struct ErrorContext {
  std::string file;   // the file read, or "command line"; empty when none
  int row = 0;        // 1-based (the header is row 1); 0 when not tied to a row
  std::string field;  // the column, key or flag; empty when none
};

class Error {
 public:
  explicit Error(ErrorKind kind, ErrorContext context = {})
      : kind_(kind), context_(std::move(context)) {}
  virtual ~Error() = default;
  ErrorKind kind() const { return kind_; }
  const ErrorContext& context() const { return context_; }

 private:
  ErrorKind kind_;
  ErrorContext context_;
};

}  // namespace ecorail
