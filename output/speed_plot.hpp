// Speed-distance plot as SVG, drawn by gnuplot: the driven speed over the speed limits in the
// upper panel and the gradient profile in the lower one, dwells and section boundaries
// included for journeys. The SVG is written atomically; a missing gnuplot is a clear error.
#pragma once

#include <filesystem>
#include <string>

#include "output/timeline.hpp"

namespace ecorail::output {

void write_speed_plot_svg(const std::filesystem::path& path, const Timeline& timeline,
                          const std::string& title);

}  // namespace ecorail::output
