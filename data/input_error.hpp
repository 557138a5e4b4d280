// InputError: bad user input in a file or a flag (ecorail::Error of kind kBadInput). It names the
// file, the row (1-based, the header being row 1; 0 when the problem is not tied to a row) and
// the field, and says what was expected. The program prints what() and exits with code 2.
#pragma once

#include <stdexcept>
#include <string>

#include "base/error.hpp"

namespace ecorail::data {

class InputError : public std::runtime_error, public Error {
 public:
  InputError(std::string file, int row, std::string field, const std::string& expected);
  const std::string& file() const { return context().file; }
  int row() const { return context().row; }
  const std::string& field() const { return context().field; }
  // What was expected, as given (without the file, row and field): for a message that wraps
  // this one without saying "expected" twice.
  const std::string& expected() const { return expected_; }

 private:
  std::string expected_;
};

}  // namespace ecorail::data
