// Outputs of the many-train service simulation (question 2.2): every train's speed-distance
// profile as one long-format CSV (train, clock time, position, speed, separation cap, line
// limit) and one train's profile as a plot (SVG or PNG by gnuplot) with the separation cap it
// ran under and the line limit drawn. The writers format what service/profiles.* computed.
#pragma once

#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

#include "output/gnuplot.hpp"
#include "service/profiles.hpp"

namespace ecorail::output {

// One profile per train (train ids from 1, in departure order); the cap column is empty where
// no train ahead constrains.
void write_profiles_csv(std::ostream& out,
                        const std::vector<std::vector<service::ProfilePoint>>& profiles);

void write_profile_plot(const std::filesystem::path& file, PlotFormat format,
                        const std::vector<service::ProfilePoint>& profile,
                        const std::string& title);

}  // namespace ecorail::output
