// Writers of the per-second table: CSV and XLSX with the published columns (time, speed in cm/s
// and km/h, acceleration, distance, kilometre post, gradient, traction force, traction power)
// followed by our own (time in s, braking force, speed limit, regime, section, dwelling, curve
// radius). The XLSX adds a summary sheet of key figures, numbers stored as numbers. The path
// writers are atomic (a failed write leaves no file); the stream and file forms are for
// callers that commit several outputs together (data::OutputBatch).
#pragma once

#include <cstdint>
#include <filesystem>
#include <ostream>
#include <string>
#include <variant>
#include <vector>

#include "output/timeline.hpp"

namespace ecorail::output {

// One key/value line of the XLSX summary sheet. Numbers are stored as numbers (the key names
// the unit, e.g. "traction_energy_kJ"); text is for names and labels.
struct SummaryRow {
  std::string key;
  std::variant<std::string, double, std::int64_t> value;
};
using SummaryRows = std::vector<SummaryRow>;

// The table's column names, in order.
const std::vector<std::string>& profile_columns();

void write_profile_csv(std::ostream& out, const Timeline& rows);
// Writes the workbook to file directly (not atomically: file should be a temporary).
void write_profile_xlsx_file(const std::filesystem::path& file, const Timeline& rows,
                             const SummaryRows& summary);

void write_profile_csv(const std::filesystem::path& path, const Timeline& rows);
void write_profile_xlsx(const std::filesystem::path& path, const Timeline& rows,
                        const SummaryRows& summary);

}  // namespace ecorail::output
