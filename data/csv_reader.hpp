// A small reader for the comma-separated tables of line data: a header row naming the columns,
// then one record per line. Fields are trimmed of blanks (and of the CR of CRLF files), blank
// lines are skipped, a UTF-8 byte-order mark is ignored. There is no quoting: a field cannot
// hold a comma. Row numbers are 1-based file lines, the header being row 1, so an error names
// the line a text editor shows. Every problem is an InputError naming file, row and field.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace ecorail::data {

struct CsvRow {
  int row = 0;                      // 1-based line in the file
  std::vector<std::string> fields;  // trimmed, one per header column
};

class CsvTable {
 public:
  // Parses text; file is the name used in error messages.
  static CsvTable parse(std::string_view text, std::string file);
  // Reads and parses a file; a missing or unreadable file is an InputError naming it.
  static CsvTable read(const std::filesystem::path& path);

  const std::string& file() const { return file_; }
  const std::vector<std::string>& header() const { return header_; }
  const std::vector<CsvRow>& rows() const { return rows_; }
  // Index of the named column; an InputError naming the file and the column when absent.
  std::size_t column(const std::string& name) const;
  // Whether the header has the named column (for optional columns).
  bool has_column(const std::string& name) const;
  // The field of a row in a column, as text or as a finite number (InputError otherwise).
  const std::string& text(const CsvRow& row, std::size_t column) const;
  double number(const CsvRow& row, std::size_t column) const;

 private:
  std::string file_;
  std::vector<std::string> header_;
  std::vector<CsvRow> rows_;
};

// Parses all of text as a finite decimal number (an optional sign, digits, point, exponent);
// anything else ("", "abc", "1.2x", "nan", "inf") is InputError(file, row, field, "a number").
double parse_number(std::string_view text, const std::string& file, int row,
                    const std::string& field);
// How a clock time of two fields reads: "MM:SS" (per-second logs) or "HH:MM" (a start time).
enum class TwoFieldClock { MinutesSeconds, HoursMinutes };
// Parses a clock time "H:MM:SS" (seconds may have a fraction) or two fields read as two_fields
// into seconds; minutes and seconds below 60, only the last field fractional, nothing negative.
// Anything else is InputError(file, row, field, expected + "; got '<text>'").
double parse_clock_s(const std::string& text, TwoFieldClock two_fields, const std::string& file,
                     int row, const std::string& field, const std::string& expected);
// A number for messages: up to 10 significant digits, no trailing zeros ("355", "23803.34").
std::string format_number(double value);
// Reads a whole file as text; a missing, unreadable or non-regular file is an InputError. With
// register_files_read() on (data/atomic_file.hpp) the file becomes an input of the run, which
// no output may replace.
std::string read_text_file(const std::filesystem::path& path);

}  // namespace ecorail::data
