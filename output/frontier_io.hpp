// Frontiers in and out: JSON (also the cache format, read back by frontier_from_json), CSV with
// one row per point and a section column, and the energy-time plot (SVG or PNG by the file
// name), each curve in its own colour and line style.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <ostream>
#include <string>
#include <vector>

#include "dp/frontier.hpp"
#include "output/gnuplot.hpp"

namespace ecorail::output {

struct LabelledFrontier {
  std::string from, to;
  dp::Frontier frontier;
  // Read back from the frontier cache rather than computed by this run. frontier_json writes
  // it as "from_cache"; frontier_from_json sets it, since the JSON it reads is a stored one.
  bool from_cache = false;
};

nlohmann::json frontier_json(const LabelledFrontier& f);
LabelledFrontier frontier_from_json(const nlohmann::json& j);
void write_frontiers_csv(std::ostream& out, const std::vector<LabelledFrontier>& frontiers);
void write_frontiers_csv(const std::filesystem::path& path,
                         const std::vector<LabelledFrontier>& frontiers);

// Line style of curve i: colour, dash type and point type, no two curves alike for i < 60.
struct CurveStyle {
  std::string colour;  // "#rrggbb"
  int dash_type = 1;   // gnuplot dt
  int point_type = 7;  // gnuplot pt
};
CurveStyle frontier_curve_style(std::size_t i);
// The gnuplot script; it reads "frontier.dat" (one data block per frontier).
std::string frontiers_plot_script(const std::vector<LabelledFrontier>& frontiers,
                                  const std::string& title, const std::string& objective,
                                  PlotFormat format, const std::filesystem::path& output_file);
// Draws straight into file (not atomically: file should be a temporary).
void write_frontiers_plot_file(const std::filesystem::path& file,
                               const std::vector<LabelledFrontier>& frontiers,
                               const std::string& title, const std::string& objective,
                               PlotFormat format);
// Atomic; the format follows the name (.svg or .png; other names are refused). objective
// names the energy on the vertical axis (e.g. "traction input energy"); empty: "energy".
void write_frontiers_plot(const std::filesystem::path& path,
                          const std::vector<LabelledFrontier>& frontiers, const std::string& title,
                          const std::string& objective = "");
// Kept for existing callers; the format follows the name like write_frontiers_plot.
void write_frontiers_plot_svg(const std::filesystem::path& path,
                              const std::vector<LabelledFrontier>& frontiers,
                              const std::string& title);

}  // namespace ecorail::output
