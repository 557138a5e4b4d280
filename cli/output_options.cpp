#include "cli/output_options.hpp"

#include "output/run_json.hpp"

#include <filesystem>

#include "data/atomic_file.hpp"
#include "data/input_error.hpp"
#include "output/speed_plot.hpp"

namespace ecorail::cli {

void add_output_options(CLI::App* cmd, OutputOptions& o) {
  cmd->add_option("--json", o.json, "write the result as JSON");
  cmd->add_option("--csv", o.csv, "write the per-second table as CSV");
  cmd->add_option("--xlsx", o.xlsx, "write the per-second table and a summary as XLSX");
  cmd->add_option("--plot", o.plot, "write the speed-distance plot as SVG (gnuplot)");
}

void check_output_targets(const OutputOptions& o) {
  for (const auto& [flag, path] : {std::pair{"--json", o.json}, std::pair{"--csv", o.csv},
                                   std::pair{"--xlsx", o.xlsx}, std::pair{"--plot", o.plot}}) {
    if (path.empty()) continue;
    const auto parent = std::filesystem::absolute(path).parent_path();
    if (!std::filesystem::is_directory(parent)) {
      throw data::InputError(
          "command line", 0, flag,
          "a file in an existing directory; '" + parent.string() + "' does not exist");
    }
  }
}

void write_outputs(const OutputOptions& o, const nlohmann::json& report,
                   const output::Timeline& timeline, const std::string& title,
                   const output::SummaryRows& summary) {
  if (!o.json.empty()) {
    output::write_json(o.json, report);
  }
  if (!o.csv.empty() || !o.xlsx.empty()) {
    const output::Timeline rows = output::per_second(timeline);
    if (!o.csv.empty()) output::write_profile_csv(o.csv, rows);
    if (!o.xlsx.empty()) output::write_profile_xlsx(o.xlsx, rows, summary);
  }
  if (!o.plot.empty()) output::write_speed_plot_svg(o.plot, timeline, title);
}

}  // namespace ecorail::cli
