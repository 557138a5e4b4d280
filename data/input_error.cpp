#include "data/input_error.hpp"

#include <utility>

namespace ecorail::data {

namespace {
std::string format_message(const std::string& file, int row, const std::string& field,
                           const std::string& expected) {
  std::string msg = file.empty() ? std::string("<input>") : file;
  msg += ": ";
  if (row > 0) msg += "row " + std::to_string(row);
  if (!field.empty()) {
    if (row > 0) msg += ", ";
    msg += "field '" + field + "'";
  }
  if (row > 0 || !field.empty()) msg += ": ";
  msg += "expected " + expected;
  return msg;
}
}  // namespace

InputError::InputError(std::string file, int row, std::string field, const std::string& expected)
    : std::runtime_error(format_message(file, row, field, expected)),
      Error(ErrorKind::kBadInput, ErrorContext{std::move(file), row, std::move(field)}),
      expected_(expected) {}

}  // namespace ecorail::data
