// The plots of a Monte Carlo run (question 3.2), drawn by gnuplot as SVG: the histogram of
// arrival lateness (pooled over the days, log scale: most arrivals are on time), the histogram
// of the days' substation energy, and the punctuality per station. Every text reaches gnuplot
// through gnuplot_quote.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace ecorail::output {

// counts[i]: arrivals with lateness in [i, i + 1) s (the last bin: above).
void write_lateness_histogram(const std::filesystem::path& file,
                              const std::vector<std::int64_t>& counts, const std::string& title);
// One value per day (kJ), drawn in 30 bins.
void write_energy_histogram(const std::filesystem::path& file, const std::vector<double>& day_kJ,
                            const std::string& title);
// Share of punctual arrivals per station (names in the order of travel).
void write_punctuality_plot(const std::filesystem::path& file,
                            const std::vector<std::string>& stations,
                            const std::vector<double>& punctuality, const std::string& title);

}  // namespace ecorail::output
