// Writers of the per-second table: CSV and XLSX with the published columns (time, speed in cm/s
// and km/h, acceleration, distance, kilometre post, gradient, traction force, traction power)
// followed by our own (time in s, braking force, speed limit, regime, section, dwelling).
// Both write atomically: a failed write leaves no file.
#pragma once

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "output/timeline.hpp"

namespace ecorail::output {

// Key/value lines for the XLSX summary sheet.
using SummaryRows = std::vector<std::pair<std::string, std::string>>;

void write_profile_csv(const std::filesystem::path& path, const Timeline& rows);
void write_profile_xlsx(const std::filesystem::path& path, const Timeline& rows,
                        const SummaryRows& summary);

}  // namespace ecorail::output
