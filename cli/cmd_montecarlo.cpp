// `ecorail montecarlo`: whole service days under random delays (question 3.2). Reads the plan
// (the 2.1 reference plan or a timetable CSV), simulates days [first, last) of the run (all of
// them, or one shard: --shard i/N) with recovery::MonteCarlo and writes the statistics with
// their confidence intervals, every day's record, and the plots. `ecorail montecarlo merge`
// combines shards into the statistics of the whole run, to the last digit; `--adjust` searches
// the plan family of recovery/plan_adjustment.hpp and writes the chosen plan as a timetable CSV
// (docs/delays.md).

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "cli/commands.hpp"
#include "cli/errors.hpp"
#include "cli/journey_solve.hpp"
#include "cli/montecarlo_options.hpp"
#include "cli/output_options.hpp"
#include "cli/plan_input.hpp"
#include "cli/problem_options.hpp"
#include "cli/progress_line.hpp"
#include "data/atomic_file.hpp"
#include "data/csv_reader.hpp"
#include "data/input_error.hpp"
#include "data/train_io.hpp"
#include "dp/section_library.hpp"
#include "output/frontier_cache.hpp"
#include "output/gnuplot.hpp"
#include "output/montecarlo_plots.hpp"
#include "output/montecarlo_tables.hpp"
#include "output/section_run_cache.hpp"
#include "output/timetable_csv_writer.hpp"
#include "recovery/monte_carlo.hpp"
#include "recovery/monte_carlo_run.hpp"
#include "recovery/plan_adjustment.hpp"

namespace ecorail::cli {

namespace {

std::vector<std::string> svg_paths(const std::string& prefix) {
  if (prefix.empty()) return {};
  return {prefix + "_lateness.svg", prefix + "_energy.svg", prefix + "_punctuality.svg"};
}

// Outputs of a run or a merge: the JSON, the per-day CSV and the three plots.
void add_run_outputs(data::OutputBatch& batch, const recovery::MonteCarloRun& run,
                     const std::string& shard, const MonteCarloArgs& a) {
  if (!a.json.empty()) {
    const nlohmann::json j = recovery::run_json(run, shard);
    batch.add(a.json, [j](std::ostream& o) { o << j.dump(1) << "\n"; });
  }
  if (!a.csv.empty())
    batch.add(a.csv, [&run](std::ostream& o) { output::write_day_records_csv(o, run.days); });
  const std::vector<std::string> svgs = svg_paths(a.svg_prefix);
  if (svgs.empty()) return;
  const recovery::MonteCarloStatistics s = recovery::summarise(run.days, run.histogram);
  const double early = run.config.value("run_early_s", 0.0);
  const std::string what =
      run.config.value("plan", std::string("plan")) +
      (early > 0.0 ? ", run " + data::format_number(early) + " s early" : std::string()) + ", " +
      run.config.value("recovery", std::string("")) + " recovery, " +
      std::to_string(run.days.size()) + " days";
  batch.add_produced(svgs[0], [&run, what](const std::filesystem::path& f) {
    output::write_lateness_histogram(f, run.histogram, "Arrival lateness: " + what);
  });
  std::vector<double> energy;
  for (const auto& d : run.days) energy.push_back(d.substation_kJ);
  batch.add_produced(svgs[1], [energy, what](const std::filesystem::path& f) {
    output::write_energy_histogram(f, energy, "Substation energy per day: " + what);
  });
  std::vector<std::string> names;
  std::vector<double> punct;
  for (const recovery::StationPunctuality& p : recovery::station_punctuality(s, run.stations)) {
    names.push_back(p.station);
    punct.push_back(p.punctuality);
  }
  batch.add_produced(svgs[2], [names, punct, what](const std::filesystem::path& f) {
    output::write_punctuality_plot(f, names, punct, "Punctuality per station: " + what);
  });
}

void check_targets(const MonteCarloArgs& a, bool adjust) {
  std::vector<OutputTarget> targets = {{"--json", a.json, false}};
  if (adjust)
    targets.push_back({"--adjusted-csv", a.adjusted_csv, false});
  else
    targets.push_back({"--csv", a.csv, false});
  for (const std::string& s : svg_paths(a.svg_prefix)) targets.push_back({"--svg-prefix", s, true});
  check_output_targets(targets);
}

void run_merge(const MonteCarloArgs& a) {
  if (a.merge_files.empty()) bad("merge", "at least one shard JSON");
  check_targets(a, false);
  std::vector<recovery::MonteCarloRun> shards;
  for (const std::string& f : a.merge_files) {
    std::ifstream in(f);
    if (!in) throw data::InputError(f, 0, "file", "a readable Monte Carlo shard JSON");
    nlohmann::json j;
    try {
      in >> j;
      shards.push_back(recovery::run_from_json(j));
    } catch (const std::exception& e) {
      throw data::InputError(f, 0, "json", std::string("a Monte Carlo shard JSON: ") + e.what());
    }
  }
  recovery::MonteCarloRun run;
  try {
    run = recovery::merge_runs(shards, a.merge_files);
  } catch (const std::invalid_argument& e) {
    throw data::InputError("montecarlo merge", 0, "shards", e.what());
  }
  const recovery::MonteCarloSummary sm = recovery::run_summary(run);
  std::FILE* out = a.json == "-" || a.csv == "-" ? stderr : stdout;
  std::fprintf(out, "merged %zu shards: ", shards.size());
  std::fputs(sm.BriefReport().c_str(), out);
  data::OutputBatch batch;
  add_run_outputs(batch, run, "", a);
  batch.commit();
}

void run_montecarlo(const MonteCarloArgs& a) {
  if (a.reference == !a.plan_file.empty()) bad("--plan/--reference", "exactly one of them");
  const recovery::MonteCarloOptions o = simulation_options(a);
  const std::pair<int, int> shard = shard_of(a);
  const recovery::PlanAdjustmentOptions adj = adjustment_options(a);
  check_targets(a, a.adjust);
  const Problem p = load_fleet_problem(a.problem, "--train-file");
  recovery::PlanStops ps =
      recovery::read_plan_stops(p.line, a.reference ? std::string() : a.plan_file);
  recovery::Plan& plan = ps.plan;
  // Before any engine is built: the shard holds days, and its day records fit in memory.
  {
    const auto [from, to] =
        recovery::shard_days(static_cast<std::uint64_t>(a.days), shard.first, shard.second);
    if (to <= from)
      bad("--shard", "a shard that holds days: shard " + a.shard + " of " + std::to_string(a.days) +
                         " days is empty (use at most " + std::to_string(a.days) + " shards)");
    if (!a.adjust) check_day_memory(to - from, ps.stops.size());
  }
  const std::vector<std::string>& stops = ps.stops;
  const std::unique_ptr<dp::SectionLibrary> lib =
      plan_library(p, a.problem, stops, a.frontier_span_s);
  const dp::SectionLibrary& library = *lib;
  if (a.reference) plan = recovery::reference_plan_on(library, stops);
  output::FileFrontierStore store(cache_directory(a.cache_dir));
  output::FileSectionRunStore run_store(cache_directory(a.cache_dir) / "section-runs");
  StageProgress progress("ecorail montecarlo", a.quiet);
  auto wall0 = std::chrono::steady_clock::now();
  std::unique_ptr<recovery::SectionRuns> runs;
  std::unique_ptr<recovery::MonteCarlo> mc;
  try {
    progress.update("section runs", 0, 0);
    runs = std::make_unique<recovery::SectionRuns>(library, a.no_cache ? nullptr : &store,
                                                   o.knot_step_s, o.bin_step_s,
                                                   a.no_cache ? nullptr : &run_store);
    mc = std::make_unique<recovery::MonteCarlo>(library, plan, o, *runs);
  } catch (const std::invalid_argument& e) {
    throw data::InputError(a.reference ? "command line" : a.plan_file, 0,
                           a.reference ? "--reference" : "--plan", e.what());
  }
  const std::string plan_name =
      a.reference ? "reference" : std::filesystem::path(a.plan_file).filename().string();
  if (a.adjust) {
    recovery::PlanAdjustmentResult r = recovery::adjust_plan(
        library, plan, o, *runs, adj, std::function<void(int, int)>([&](int d, int t) {
          progress.update("candidate plan", d, t);
        }));
    std::FILE* out = a.json == "-" ? stderr : stdout;
    std::fputs(r.summary.FullReport().c_str(), out);
    std::fprintf(out, "  %5s %6s %6s %10s %10s %10s %8s %16s %16s %16s\n", "theta", "dwell+",
                 "early", "punctual", "+-", "mean_late", "p95", "substation_kJ", "+-", "plan_kJ");
    for (std::size_t i = 0; i < r.candidates.size(); ++i) {
      const auto& c = r.candidates[i];
      const auto& s = c.statistics;
      std::fprintf(out, "%s %5.2f %6.1f %6.1f %10.5f %10.5f %10.3f %8.2f %16.1f %16.1f %16.1f\n",
                   i == r.summary.chosen ? "*" : " ", c.theta, c.extra_dwell_s, c.run_early_s,
                   s.punctuality.mean, s.punctuality.ci95, s.mean_lateness_s.mean,
                   s.p95_lateness_s.mean, s.substation_kJ.mean, s.substation_kJ.ci95,
                   c.plan_substation_kJ);
    }
    const nlohmann::json j = recovery::plan_adjustment_json(r, plan_name, a.seed, a.search_days);
    data::OutputBatch batch;
    const recovery::Plan chosen = r.chosen().plan;
    std::vector<double> positions_m = {0.0};
    for (std::size_t i = 0; i < library.size(); ++i)
      positions_m.push_back(positions_m.back() + library.route(i).length_m());
    batch.add(a.adjusted_csv, [&chosen, &positions_m](std::ostream& o) {
      output::write_timetable_csv(o, chosen, positions_m);
    });
    if (!a.json.empty()) batch.add(a.json, [&j](std::ostream& o) { o << j.dump(1) << "\n"; });
    batch.commit();
    return;
  }
  const auto [first, last] =
      recovery::shard_days(static_cast<std::uint64_t>(a.days), shard.first, shard.second);
  progress.update("day", 0, static_cast<int>(last - first));
  recovery::MonteCarloRunInfo info;
  info.plan_name = plan_name;
  info.days_total = static_cast<std::uint64_t>(a.days);
  info.frontier_span_s = a.frontier_span_s;
  info.ds_m = a.problem.ds_m;
  info.dv_kmh = a.problem.dv_kmh;
  info.line_checksum = p.line.checksum();
  info.train_checksum = data::train_checksum(p.train);
  const recovery::MonteCarloDays result = recovery::simulate_days(
      *mc, *runs, first, last, a.problem.threads, info,
      [&](int d, int t) { progress.update("day", d, t); }, wall0);
  const recovery::MonteCarloRun& run = result.run;
  const recovery::MonteCarloSummary& sm = result.summary;
  std::FILE* out = a.json == "-" || a.csv == "-" ? stderr : stdout;
  std::fputs((a.full_report ? sm.FullReport() : sm.BriefReport()).c_str(), out);
  std::fflush(out);
  data::OutputBatch batch;
  add_run_outputs(batch, run, a.shard.empty() ? "" : a.shard, a);
  batch.commit();
}

}  // namespace

void add_montecarlo_command(CLI::App& app) {
  auto args = std::make_shared<MonteCarloArgs>();
  CLI::App* cmd = app.add_subcommand(
      "montecarlo", "service days under random delays: punctuality, lateness, energy (3.2)");
  add_montecarlo_options(cmd, *args);
  CLI::App* merge = cmd->add_subcommand("merge", "combine shard JSONs into the whole run");
  merge->add_option("shards", args->merge_files, "shard JSON files")->required();
  input_files(merge, {"shards"});
  merge->add_option("--json", args->json, "write the merged statistics (JSON)");
  merge->add_option("--csv", args->csv, "write one row per day (CSV)");
  merge->add_option("--svg-prefix", args->svg_prefix,
                    "write P_lateness.svg, P_energy.svg and P_punctuality.svg");
  cmd->require_subcommand(0, 1);
  merge->callback([args] { run_merge(*args); });
  cmd->callback([args, merge] {
    if (merge->parsed()) return;
    run_montecarlo(*args);
  });
}

}  // namespace ecorail::cli
