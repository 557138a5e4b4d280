#include "cli/plan_input.hpp"

#include <cstdio>

#include "cli/errors.hpp"
#include "cli/output_options.hpp"
#include "output/frontier_cache.hpp"

namespace ecorail::cli {

std::unique_ptr<dp::SectionLibrary> plan_library(const Problem& p, const ProblemOptions& o,
                                                 const std::vector<std::string>& stops,
                                                 double frontier_span_s) {
  dp::SectionLibraryOptions options;
  options.engine = engine_options(o);
  options.frontier_span_s = frontier_span_s;
  require_valid(options);
  return recovery::plan_section_library(p.line, p.train, stops, options);
}

std::filesystem::path cache_directory(const std::string& cache_dir) {
  return cache_dir.empty() ? output::FileFrontierStore::default_directory()
                           : std::filesystem::path(cache_dir);
}

void add_plan_source_options(CLI::App* cmd, std::string& plan_file, bool& reference) {
  cmd->add_option("--plan", plan_file,
                  "timetable CSV as `ecorail timetable evaluate|optimise --csv` writes it");
  cmd->add_flag("--reference", reference,
                "the 2.1 plan: 30 s dwells, optimal split of 1726 s, 100 trains uniform over "
                "63900 s");
  input_files(cmd, {"--plan"});
}

void add_plan_engine_options(CLI::App* cmd, ProblemOptions& problem, double& frontier_span_s,
                             std::string& cache_dir, bool& no_cache) {
  cmd->add_option("--frontier-span", frontier_span_s,
                  "each section's frontier covers [T_min, T_min + span] (s)")
      ->capture_default_str();
  cmd->add_option("--line", problem.line_path, "line (default: the embedded reference line)");
  cmd->add_option("--train-file", problem.train_path,
                  "train TOML or TTOBench JSON (default: the reference train)");
  input_files(cmd, {"--line", "--train-file"});
  cmd->add_option("--ds", problem.ds_m, "grid position step in m")->capture_default_str();
  cmd->add_option("--dv", problem.dv_kmh, "grid speed step in km/h")->capture_default_str();
  cmd->add_option("--threads", problem.threads, "OpenMP threads (default: all cores)");
  cmd->add_option("--cache-dir", cache_dir,
                  "frontier cache directory (default: $XDG_CACHE_HOME/ecorail/frontiers)");
  cmd->add_flag("--no-cache", no_cache, "compute every frontier afresh");
}

StageProgress::StageProgress(std::string label, bool quiet)
    : line_(label, quiet),
      label_(std::move(label)),
      lines_(!quiet && !Progress::stderr_is_terminal()) {}

void StageProgress::update(const char* stage, int done, int total) {
  line_.update(stage, done, total);
  if (!lines_) return;
  std::lock_guard<std::mutex> lock(mutex_);
  if (last_stage_ == stage) return;
  last_stage_ = stage;
  std::fprintf(stderr, "%s: %s\n", label_.c_str(), stage);
  std::fflush(stderr);
}

dp::ProgressFn StageProgress::callback() {
  return [this](const char* stage, int done, int total) { update(stage, done, total); };
}

}  // namespace ecorail::cli
