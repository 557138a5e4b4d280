// Output flags shared by the engine commands (--json, --csv, --xlsx, --plot) and the writing of
// them. Target directories are checked before any work starts, and every file is written
// atomically, so a failed run leaves no partial output behind.
#pragma once

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <string>

#include "output/profile_writers.hpp"
#include "output/timeline.hpp"

namespace ecorail::cli {

struct OutputOptions {
  std::string json, csv, xlsx, plot;
};

void add_output_options(CLI::App* cmd, OutputOptions& o);
// InputError if a target's directory does not exist.
void check_output_targets(const OutputOptions& o);
void write_outputs(const OutputOptions& o, const nlohmann::json& report,
                   const output::Timeline& timeline, const std::string& title,
                   const output::SummaryRows& summary);

}  // namespace ecorail::cli
