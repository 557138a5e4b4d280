#include "cli/output_options.hpp"

#include <algorithm>
#include <filesystem>
#include <sstream>
#include <stdexcept>

#include "data/atomic_file.hpp"
#include "data/csv_reader.hpp"
#include "data/input_error.hpp"
#include "output/gnuplot.hpp"
#include "output/gtfs_writer.hpp"
#include "output/provenance.hpp"
#include "output/run_json.hpp"
#include "output/solve_reports.hpp"
#include "output/speed_plot.hpp"

namespace ecorail::cli {

namespace {

// Two spellings of one file (a/../b, ./b, a link to a directory) compare equal.
std::filesystem::path identity(const std::string& path) {
  if (data::is_stdout_path(path)) return "-";
  std::error_code ec;
  const auto canonical = std::filesystem::weakly_canonical(std::filesystem::absolute(path), ec);
  return ec ? std::filesystem::absolute(path).lexically_normal() : canonical;
}

std::string objective_text(const std::string& name) {
  if (name == "traction") return "least traction energy (work at the wheel / traction efficiency)";
  if (name == "net") return "least net energy (traction input - regenerated)";
  return name;
}

output::SpeedPlotLabels plot_labels(const OutputOptions& o, const nlohmann::json& report) {
  output::SpeedPlotLabels labels;
  labels.x_axis = o.plot_x == "time" ? output::PlotAxis::Time : output::PlotAxis::Distance;
  if (report.contains("stops") && report["stops"].is_array()) {
    for (const auto& s : report["stops"]) labels.stations.push_back(s.get<std::string>());
  } else if (report.contains("from") && report.contains("to")) {
    labels.stations = {report["from"].get<std::string>(), report["to"].get<std::string>()};
  }
  std::string objective;
  if (report.contains("objective") && report["objective"].is_string()) {
    objective = report["objective"].get<std::string>();
  } else if (const auto ptr = nlohmann::json::json_pointer("/provenance/options/objective");
             report.contains(ptr) && report[ptr].is_string()) {
    objective = report[ptr].get<std::string>();
  }
  labels.objective = objective_text(objective);
  return labels;
}

}  // namespace

void add_output_options(CLI::App* cmd, OutputOptions& o) {
  cmd->add_option("--json", o.json, "write the result as JSON ('-': standard output)");
  cmd->add_option("--csv", o.csv, "write the per-second table as CSV ('-': standard output)");
  cmd->add_option("--xlsx", o.xlsx, "write the per-second table and a summary as XLSX");
  cmd->add_option("--plot", o.plot,
                  "write the speed plot (gnuplot): FILE.svg or FILE.png ('-': SVG on standard "
                  "output)");
  cmd->add_option("--plot-x", o.plot_x, "horizontal axis of the speed plot: distance or time")
      ->check(CLI::IsMember({"distance", "time"}))
      ->capture_default_str();
}

void input_files(CLI::App* cmd, std::initializer_list<const char*> flags) {
  for (const char* flag : flags) {
    CLI::Option* option = nullptr;
    try {
      option = cmd->get_option(flag);
    } catch (const CLI::OptionNotFound&) {
      throw std::logic_error(std::string("input_files: ") + cmd->get_name() + " has no " + flag);
    }
    const std::string name = flag;
    option->each([name](const std::string& path) { data::register_input(name, path); });
  }
}

void check_output_targets(const std::vector<OutputTarget>& targets) {
  std::vector<std::pair<std::filesystem::path, std::string>> seen;
  std::vector<output::PlotFormat> checked_formats;  // gnuplot is asked once per format
  for (const auto& t : targets) {
    if (t.path.empty()) continue;
    // A file in a directory still to be made: only the run's inputs could be in its way.
    const std::string problem = t.new_directory ? (data::input_read_as(t.path).empty()
                                                       ? ""
                                                       : "'" + t.path + "' is an input of this run")
                                                : data::output_target_problem(t.path);
    if (!problem.empty()) {
      throw data::InputError("command line", 0, t.flag,
                             "a file that can be written or replaced; " + problem);
    }
    const auto id = identity(t.path);
    for (const auto& [other, flag] : seen) {
      if (other == id) {
        throw data::InputError("command line", 0, t.flag,
                               "a path other than " + flag + "'s; got '" + t.path + "' twice");
      }
    }
    seen.emplace_back(id, t.flag);
    if (t.plot) {
      if (!output::plot_format_for(t.path)) {
        throw data::InputError("command line", 0, t.flag,
                               "a plot file ending in .svg or .png; got '" + t.path + "'");
      }
      const auto format = *output::plot_format_for(t.path);
      if (std::find(checked_formats.begin(), checked_formats.end(), format) ==
          checked_formats.end()) {
        if (const std::string problem = output::gnuplot_problem(format); !problem.empty()) {
          throw data::InputError("command line", 0, t.flag, "a plot gnuplot can draw; " + problem);
        }
        checked_formats.push_back(format);
      }
    }
  }
}

void check_output_targets(const OutputOptions& o) {
  std::vector<OutputTarget> targets = {{"--json", o.json, false},
                                       {"--csv", o.csv, false},
                                       {"--xlsx", o.xlsx, false},
                                       {"--plot", o.plot, true}};
  const std::vector<OutputTarget> gtfs = gtfs_targets(o);
  targets.insert(targets.end(), gtfs.begin(), gtfs.end());  // no GTFS file is another's path
  check_output_targets(targets);
  if (data::is_stdout_path(o.xlsx)) {
    throw data::InputError("command line", 0, "--xlsx", "a file (XLSX is not written to '-')");
  }
}

nlohmann::json run_provenance(const Problem& problem, const ProblemOptions& options,
                              const nlohmann::json& extra_options) {
  output::RunInputs inputs;
  if (!options.line_path.empty()) inputs.line = options.line_path;
  if (!options.train_path.empty()) inputs.train = options.train_path;
  inputs.from = options.from;
  inputs.to = options.to;
  inputs.objective = options.objective;
  inputs.ds_m = options.ds_m;
  inputs.dv_kmh = options.dv_kmh;
  return output::run_provenance_json(problem.line, problem.train, inputs, extra_options);
}

void write_outputs(const OutputOptions& o, const nlohmann::json& report,
                   const output::Timeline& timeline, const std::string& title,
                   const output::SummaryRows& summary, const physics::Trip* trip,
                   const data::Line* line) {
  data::OutputBatch batch;
  if (!o.gtfs.empty()) {
    if (!trip || !line) throw std::logic_error("--gtfs without a trip and line to write");
    add_gtfs_outputs(batch, o, {{"ecorail-1", *trip}}, *line);
  }
  if (!o.json.empty()) {
    batch.add(o.json, [&](std::ostream& out) { output::write_json(out, report); });
  }
  if (!o.csv.empty() || !o.xlsx.empty()) {
    const output::Timeline rows = output::per_second(timeline);
    if (!o.csv.empty()) {
      batch.add(o.csv, [&](std::ostream& out) { output::write_profile_csv(out, rows); });
    }
    if (!o.xlsx.empty()) {
      batch.add_produced(o.xlsx, [&](const std::filesystem::path& tmp) {
        output::write_profile_xlsx_file(tmp, rows, summary);
      });
    }
  }
  if (!o.plot.empty()) {
    const auto format = output::plot_format_for(o.plot);
    if (!format) throw std::runtime_error("cannot write " + o.plot + ": not .svg or .png");
    const auto labels = plot_labels(o, report);
    batch.add_produced(o.plot, [&](const std::filesystem::path& tmp) {
      output::write_speed_plot_file(tmp, timeline, title, labels, *format);
    });
  }
  batch.commit();
}

}  // namespace ecorail::cli
