// Frontiers in and out: JSON (also the cache format, read back by frontier_from_json), CSV with
// one row per point and a section column, and the energy-time plot.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "dp/frontier.hpp"

namespace ecorail::output {

struct LabelledFrontier {
  std::string from, to;
  dp::Frontier frontier;
};

nlohmann::json frontier_json(const LabelledFrontier& f);
LabelledFrontier frontier_from_json(const nlohmann::json& j);
void write_frontiers_csv(const std::filesystem::path& path,
                         const std::vector<LabelledFrontier>& frontiers);
void write_frontiers_plot_svg(const std::filesystem::path& path,
                              const std::vector<LabelledFrontier>& frontiers,
                              const std::string& title);

}  // namespace ecorail::output
