// `ecorail frontier`: energy-time frontiers of one section or of every section of a line, with
// a cache keyed by line, train, grid and range (output::FileFrontierStore: a corrupt or stale
// entry is recomputed, never trusted) so the fleet work can reuse them for free.
#include <cmath>
#include <cstdio>
#include <exception>
#include <optional>

#include "cli/commands.hpp"
#include "cli/errors.hpp"
#include "cli/output_options.hpp"
#include "cli/problem_options.hpp"
#include "cli/progress_line.hpp"
#include "data/atomic_file.hpp"
#include "data/csv_reader.hpp"
#include "data/input_error.hpp"
#include "data/line.hpp"
#include "data/route_builder.hpp"
#include "data/train_io.hpp"
#include "dp/section_library.hpp"
#include "dp/threads.hpp"
#include "output/frontier_cache.hpp"
#include "output/frontier_io.hpp"
#include "output/gnuplot.hpp"
#include "output/run_json.hpp"
#include "output/solve_reports.hpp"
#include "physics/units.hpp"

namespace ecorail::cli {

namespace {

struct FrontierArgs {
  ProblemOptions problem;
  double t_min = 0.0, t_max = 0.0, step = 1.0;
  bool all = false;
  std::string json, csv, plot;
  std::string cache_dir;
  bool no_cache = false;
  bool quiet = false;
};

// The cache key of one section's frontier: line and train checksums, section, grid, objective,
// range and engine version (dp::kFrontierVersion), so a stale entry is never read.
std::string cache_key(const Problem& p, const FrontierArgs& a, const std::string& from,
                      const std::string& to) {
  char text[512];
  std::snprintf(text, sizeof text,
                "%s|frontier-command|%016llx|%016llx|%s|%s|%.17g|%.17g|%s|%.17g|%.17g|%.17g|"
                "cruise %s",
                dp::kFrontierVersion, static_cast<unsigned long long>(p.line.checksum()),
                static_cast<unsigned long long>(data::train_checksum(p.train)), from.c_str(),
                to.c_str(), a.problem.ds_m, a.problem.dv_kmh, a.problem.objective.c_str(), a.t_min,
                a.t_max, a.step, a.problem.cruise.c_str());
  return text;
}

output::LabelledFrontier frontier_for(const Problem& p, const FrontierArgs& a,
                                      const dp::EngineOptions& engine_opts,
                                      const dp::FrontierOptions& options, const std::string& from,
                                      const std::string& to, output::FileFrontierStore* cache) {
  const std::string key = cache_key(p, a, from, to);
  if (cache != nullptr) {
    if (std::optional<dp::Frontier> f = cache->load(key)) {
      output::LabelledFrontier served{from, to, std::move(*f)};
      served.from_cache = true;  // said in the table and in the JSON ("from_cache")
      return served;
    }
  }
  const physics::Route route = data::build_route(p.line, from, to, p.train);
  const dp::SectionEngine engine(p.train, route, engine_opts);
  output::LabelledFrontier lf{from, to, {}};
  try {
    lf.frontier = dp::compute_frontier(engine, options);
  } catch (const dp::InfeasibleTimeError& e) {
    // Name the flag that asked for the impossible time (--tmin, else --tmax).
    const bool tmin = a.t_min > 0.0 && a.t_min < e.minimum_s();
    throw data::InputError("command line", 0, tmin ? "--tmin" : "--tmax",
                           "at least the minimum running time of " +
                               data::format_number(std::round(e.minimum_s() * 100) / 100) +
                               " s for " + from + " -> " + to + " (flat-out run); got " +
                               data::format_number(tmin ? a.t_min : a.t_max) + " s");
  }
  if (cache != nullptr) cache->save(key, lf.frontier);
  return lf;
}

void run_frontier(const FrontierArgs& a) {
  // Every output target is checked before any work.
  check_output_targets(
      {{"--json", a.json, false}, {"--csv", a.csv, false}, {"--plot", a.plot, true}});
  if (!(a.step > 0.0)) throw data::InputError("command line", 0, "--step", "a step in s > 0");
  dp::FrontierOptions options;
  options.t_min_s = a.t_min;
  options.t_max_s = a.t_max;
  options.step_s = a.step;
  const dp::EngineOptions engine_opts = engine_options(a.problem);
  require_valid(engine_opts);
  if (a.t_max > 0.0 && a.t_max < a.t_min) {
    throw data::InputError("command line", 0, "--tmax", "a time above --tmin");
  }
  if (!a.all && (a.problem.from.empty() || a.problem.to.empty())) {
    throw data::InputError("command line", 0, a.problem.from.empty() ? "--from" : "--to",
                           "a section (--from and --to), or --all");
  }
  ProblemOptions line_only = a.problem;
  line_only.from.clear();
  const Problem p = load_problem(line_only);
  std::vector<std::pair<std::string, std::string>> sections;
  if (a.all) {
    for (std::size_t i = 0; i + 1 < p.line.stations.size(); ++i) {
      sections.emplace_back(p.line.stations[i].name, p.line.stations[i + 1].name);
    }
  } else {
    const auto stops = data::stops_between(p.line, a.problem.from, a.problem.to);
    if (stops.size() != 2) {
      throw data::InputError(
          "command line", 0, "--to",
          "the station next to --from (a frontier is of one section); got '" + a.problem.to + "'");
    }
    sections.emplace_back(a.problem.from, a.problem.to);
  }
  require_valid(options);
  output::FileFrontierStore store(a.cache_dir.empty()
                                      ? output::FileFrontierStore::default_directory()
                                      : std::filesystem::path(a.cache_dir));
  output::FileFrontierStore* cache = a.no_cache ? nullptr : &store;
  const dp::ThreadScope threads(engine_opts.threads);
  // Sections are independent: with --all they are computed side by side, and the first error
  // (if any) is reported after the loop, since exceptions may not leave an OpenMP region.
  std::vector<output::LabelledFrontier> frontiers(sections.size());
  std::exception_ptr failure;
  {
    // The progress line is cleared when this block ends, before the table.
    Progress progress("ecorail frontier", a.quiet);
    // One section: progress by point; several side by side: by section.
    if (!a.all) options.progress = progress.callback();
    int sections_done = 0;
    const int n = static_cast<int>(sections.size());
#pragma omp parallel for schedule(dynamic, 1)
    for (int i = 0; i < n; ++i) {
      const auto& [from, to] = sections[i];
      try {
        frontiers[i] = frontier_for(p, a, engine_opts, options, from, to, cache);
#pragma omp critical(frontier_progress)
        if (n > 1) progress.update("section", ++sections_done, n);
      } catch (...) {
#pragma omp critical(frontier_failure)
        if (!failure) failure = std::current_exception();
      }
    }
  }
  if (failure) std::rethrow_exception(failure);
  // The frontier's energy is the objective's cost: traction input energy (traction work divided
  // by the traction efficiency) or net energy; the header says which.
  const bool net = a.problem.objective == "net";
  std::printf("%-8s %-8s %10s %8s %19s %19s %8s %7s %8s\n", "from", "to", "min_time_s", "points",
              net ? "net_E(first)_kJ" : "input_E(first)_kJ",
              net ? "net_E(last)_kJ" : "input_E(last)_kJ", "monotone", "convex", "wobbles");
  for (const auto& lf : frontiers) {
    const auto& f = lf.frontier;
    std::printf("%-8s %-8s %10.3f %8zu %19.1f %19.1f %8s %7s %8zu\n", lf.from.c_str(),
                lf.to.c_str(), f.min_time_s, f.points.size(),
                units::J_to_kJ(f.points.front().cost_J), units::J_to_kJ(f.points.back().cost_J),
                f.monotone ? "yes" : "NO", f.convex ? "yes" : "NO", f.wobbles.size());
    if (lf.from_cache) std::printf("  note: served from the cache (computed by an earlier run)\n");
    for (const auto& w : f.wobbles) {
      std::printf("  note: %s at %.1f s by %.3f kJ (grid effect; see docs/frontiers.md)\n",
                  w.kind.c_str(), w.time_s, w.size_J / 1000.0);
    }
  }
  // All outputs or none: temporaries renamed together once every one was written.
  data::OutputBatch batch;
  if (!a.json.empty()) {
    const nlohmann::json doc =
        output::frontier_report_json(frontiers, a.all, a.problem.ds_m, a.problem.dv_kmh,
                                     run_provenance(p, a.problem,
                                                    {{"tmin_s", a.t_min},
                                                     {"tmax_s", a.t_max},
                                                     {"step_s", a.step},
                                                     {"all", a.all},
                                                     {"cache", !a.no_cache}}));
    batch.add(a.json, [&](std::ostream& o) { output::write_json(o, doc); });
  }
  if (!a.csv.empty())
    batch.add(a.csv, [&](std::ostream& o) { output::write_frontiers_csv(o, frontiers); });
  if (!a.plot.empty()) {
    const std::string objective = net ? "net energy" : "traction input energy";
    batch.add_produced(a.plot, [&](const std::filesystem::path& f) {
      output::write_frontiers_plot_file(f, frontiers, "energy-time frontier", objective,
                                        *output::plot_format_for(a.plot));
    });
  }
  batch.commit();
}

}  // namespace

void add_frontier_command(CLI::App& app) {
  auto args = std::make_shared<FrontierArgs>();
  CLI::App* cmd = app.add_subcommand("frontier", "energy-time frontier of a section");
  add_problem_options(cmd, args->problem, false);
  cmd->add_option("--tmin", args->t_min, "first running time in s (default: the minimum)");
  cmd->add_option("--tmax", args->t_max, "last running time in s (default: minimum + 60)");
  cmd->add_option("--step", args->step, "time step in s")->capture_default_str();
  cmd->add_flag("--all", args->all, "every section of the line");
  cmd->add_option("--json", args->json, "write the frontier(s) as JSON");
  cmd->add_option("--csv", args->csv, "write the frontier(s) as CSV");
  cmd->add_option("--plot", args->plot, "write an energy-time plot as SVG");
  cmd->add_option("--cache-dir", args->cache_dir,
                  "cache directory (default: $XDG_CACHE_HOME/ecorail/frontiers)");
  cmd->add_flag("--no-cache", args->no_cache, "neither read nor write the cache");
  cmd->add_flag("--quiet", args->quiet, "no progress line on stderr");
  cmd->callback([args] { run_frontier(*args); });
}

}  // namespace ecorail::cli
