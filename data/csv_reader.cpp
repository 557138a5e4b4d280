#include "data/csv_reader.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <system_error>

#include "data/atomic_file.hpp"
#include "data/input_error.hpp"

namespace ecorail::data {

namespace {

std::string_view trim(std::string_view s) {
  const char* blanks = " \t\r\n\v\f";
  const auto first = s.find_first_not_of(blanks);
  if (first == std::string_view::npos) return {};
  const auto last = s.find_last_not_of(blanks);
  return s.substr(first, last - first + 1);
}

std::vector<std::string> split_fields(std::string_view line) {
  std::vector<std::string> fields;
  std::size_t start = 0;
  while (true) {
    const auto comma = line.find(',', start);
    const auto piece = line.substr(
        start, comma == std::string_view::npos ? std::string_view::npos : comma - start);
    fields.emplace_back(trim(piece));
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  return fields;
}

std::string in_quotes(std::string_view s) {
  return "'" + std::string(s) + "'";
}

}  // namespace

CsvTable CsvTable::parse(std::string_view text, std::string file) {
  CsvTable table;
  table.file_ = std::move(file);
  if (text.substr(0, 3) == "\xEF\xBB\xBF") text.remove_prefix(3);
  int line_no = 0;
  bool have_header = false;
  std::size_t pos = 0;
  while (pos <= text.size()) {
    const auto nl = text.find('\n', pos);
    const auto end = nl == std::string_view::npos ? text.size() : nl;
    const std::string_view line = text.substr(pos, end - pos);
    ++line_no;
    pos = end + 1;
    if (trim(line).empty()) {
      if (nl == std::string_view::npos) break;
      continue;
    }
    auto fields = split_fields(line);
    if (!have_header) {
      for (std::size_t i = 0; i < fields.size(); ++i) {
        if (fields[i].empty()) {
          throw InputError(
              table.file_, line_no, "",
              "a header naming every column; column " + std::to_string(i + 1) + " has no name");
        }
        for (std::size_t j = 0; j < i; ++j) {
          if (fields[j] == fields[i]) {
            throw InputError(table.file_, line_no, fields[i],
                             "each column named once; got " + in_quotes(fields[i]) + " twice");
          }
        }
      }
      table.header_ = std::move(fields);
      have_header = true;
    } else {
      if (fields.size() != table.header_.size()) {
        throw InputError(table.file_, line_no, "",
                         std::to_string(table.header_.size()) +
                             " comma-separated fields as in the header; got " +
                             std::to_string(fields.size()));
      }
      table.rows_.push_back(CsvRow{line_no, std::move(fields)});
    }
    if (nl == std::string_view::npos) break;
  }
  if (!have_header) {
    throw InputError(table.file_, 0, "", "a header row naming the columns; got an empty file");
  }
  return table;
}

CsvTable CsvTable::read(const std::filesystem::path& path) {
  return parse(read_text_file(path), path.string());
}

std::size_t CsvTable::column(const std::string& name) const {
  for (std::size_t i = 0; i < header_.size(); ++i) {
    if (header_[i] == name) return i;
  }
  std::string found;
  for (const auto& h : header_) found += (found.empty() ? "" : ", ") + h;
  throw InputError(file_, 1, name,
                   "a column named " + in_quotes(name) + " in the header; got columns " + found);
}

bool CsvTable::has_column(const std::string& name) const {
  for (const auto& h : header_) {
    if (h == name) return true;
  }
  return false;
}

const std::string& CsvTable::text(const CsvRow& row, std::size_t column) const {
  return row.fields.at(column);
}

double CsvTable::number(const CsvRow& row, std::size_t column) const {
  return parse_number(row.fields.at(column), file_, row.row, header_.at(column));
}

double parse_clock_s(const std::string& text, TwoFieldClock two_fields, const std::string& file,
                     int row, const std::string& field, const std::string& expected) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  while (true) {
    const auto colon = text.find(':', start);
    parts.push_back(
        text.substr(start, colon == std::string::npos ? std::string::npos : colon - start));
    if (colon == std::string::npos) break;
    start = colon + 1;
  }
  const InputError bad(file, row, field, expected + "; got '" + text + "'");
  if (parts.size() < 2 || parts.size() > 3) throw bad;
  double seconds = 0.0;
  for (std::size_t i = 0; i < parts.size(); ++i) {
    double v = 0.0;
    try {
      v = parse_number(parts[i], file, row, field);
    } catch (const InputError&) {
      throw bad;
    }
    const bool last = i + 1 == parts.size();
    if (v < 0.0 || (i > 0 && v >= 60.0) || (!last && v != std::floor(v))) throw bad;
    seconds = seconds * 60.0 + v;
  }
  // Two fields as hours and minutes: the value above is in minutes.
  if (parts.size() == 2 && two_fields == TwoFieldClock::HoursMinutes) seconds *= 60.0;
  return seconds;
}

double parse_number(std::string_view text, const std::string& file, int row,
                    const std::string& field) {
  const std::string_view original = text;
  text = trim(text);
  auto fail = [&]() -> InputError {
    return InputError(file, row, field,
                      "a number; got " +
                          (original.empty() ? std::string("an empty field") : in_quotes(original)));
  };
  if (text.empty()) throw fail();
  std::string_view digits = text;
  if (digits.front() == '+') digits.remove_prefix(1);
  if (digits.empty() ||
      (digits.size() < text.size() &&
       !(digits.front() == '.' || (digits.front() >= '0' && digits.front() <= '9')))) {
    throw fail();
  }
  // Only decimal notation: from_chars also reads "inf" and "nan", which no table may hold.
  for (const char c : digits) {
    if (!((c >= '0' && c <= '9') || c == '.' || c == '-' || c == '+' || c == 'e' || c == 'E')) {
      throw fail();
    }
  }
  double value = 0.0;
  const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), value,
                                         std::chars_format::general);
  if (ec != std::errc() || end != digits.data() + digits.size() || !std::isfinite(value)) {
    throw fail();
  }
  return value;
}

std::string format_number(double value) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.10g", value == 0.0 ? 0.0 : value);
  return buf;
}

std::string read_text_file(const std::filesystem::path& path) {
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (!std::filesystem::exists(status)) {
    throw InputError(path.string(), 0, "", "an existing file; got no such file");
  }
  if (!std::filesystem::is_regular_file(status)) {
    throw InputError(path.string(), 0, "", "a regular file; got a directory or special file");
  }
  if (register_files_read()) register_input("a file this run reads", path);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path.string(), 0, "", "a readable file; cannot open it");
  std::ostringstream out;
  out << in.rdbuf();
  if (in.bad()) throw InputError(path.string(), 0, "", "a readable file; reading failed");
  return out.str();
}

}  // namespace ecorail::data
