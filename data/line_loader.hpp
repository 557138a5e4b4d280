// Loading lines: the reference line compiled into the program, a directory holding the four CSV
// tables (stations.csv, gradients.csv, speed_limits.csv, curves.csv with the columns of
// data/contest/), or one TOML file with the same four tables. Every problem is an InputError
// naming file, row and field: a missing file, a missing column, a non-numeric field, a row with
// end <= start, gaps or overlaps between consecutive rows, a negative radius or limit, a
// duplicated station name.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

#include "data/csv_reader.hpp"
#include "data/line.hpp"

namespace ecorail::data {

Line default_line();
Line load_line(const std::filesystem::path& path);  // a directory of CSVs or a .toml file
// The same on tables and text already read (file names come from the tables / the label); the
// fuzz harnesses (fuzz/) call these without touching the file system.
Line line_from_csv_tables(const CsvTable& stations, const CsvTable& gradients,
                          const CsvTable& limits, const CsvTable& curves);
Line line_from_toml_text(std::string_view text, const std::string& file);

}  // namespace ecorail::data
