// `ecorail montecarlo`: whole service days under random delays (question 3.2). Reads the plan
// (the 2.1 reference plan or a timetable CSV), simulates days [first, last) of the run (all of
// them, or one shard: --shard i/N) with recovery::MonteCarlo and writes the statistics with
// their confidence intervals, every day's record, and the plots. `ecorail montecarlo merge`
// combines shards into the statistics of the whole run, to the last digit; `--adjust` searches
// the plan family of recovery/plan_adjustment.hpp and writes the chosen plan as a timetable CSV
// (docs/delays.md).
#include <unistd.h>

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
#include "cli/output_options.hpp"
#include "cli/plan_input.hpp"
#include "cli/problem_options.hpp"
#include "cli/progress_line.hpp"
#include "data/atomic_file.hpp"
#include "data/csv_reader.hpp"
#include "data/input_error.hpp"
#include "data/route_builder.hpp"
#include "data/train_io.hpp"
#include "dp/section_library.hpp"
#include "output/frontier_cache.hpp"
#include "output/gnuplot.hpp"
#include "output/montecarlo_plots.hpp"
#include "output/section_run_cache.hpp"
#include "recovery/monte_carlo.hpp"
#include "recovery/plan_adjustment.hpp"

namespace ecorail::cli {

namespace {

struct MonteCarloArgs {
  ProblemOptions problem;  // --line, --train-file, --ds, --dv, --threads
  std::string plan_file;
  bool reference = false;
  long long days = 1000;
  long long seed = 1;
  std::string recovery = "exact";
  std::string tail = "exponential:30";
  double run_early_s = 0.0;
  std::string run_early_values = "0";
  double early_s = 10.0, min_dwell_s = 30.0, takeover_s = 120.0, punctual_s = 10.0;
  double separation_s = -1.0;
  double knot_step_s = 1.0, step_s = 0.1;
  double frontier_span_s = 60.0;
  std::string shard;
  std::string cache_dir;
  bool no_cache = false, quiet = false, full_report = false;
  std::string json, csv, svg_prefix;
  // Plan adjustment.
  bool adjust = false;
  double target = 0.97;
  long long search_days = 200;
  std::string thetas = "0,0.25,0.5,0.75,1", extra_dwells = "0,3";
  std::string adjusted_csv;
  // merge
  std::vector<std::string> merge_files;
};

[[noreturn]] void bad(const std::string& flag, const std::string& expected) {
  throw data::InputError("command line", 0, flag, expected);
}

// "i/N" with 1 <= i <= N <= 100000.
std::pair<int, int> parse_shard(const std::string& text) {
  const auto slash = text.find('/');
  int i = 0, n = 0;
  char extra = 0;
  if (slash == std::string::npos || std::sscanf(text.c_str(), "%d/%d%c", &i, &n, &extra) != 2 ||
      n < 1 || n > 100000 || i < 1 || i > n)
    bad("--shard", "i/N with 1 <= i <= N (e.g. 1/2); got '" + text + "'");
  return {i, n};
}

std::vector<double> parse_list(const std::string& text, const std::string& flag) {
  std::vector<double> out;
  std::size_t at = 0;
  while (at <= text.size()) {
    const std::size_t comma = std::min(text.find(',', at), text.size());
    const std::string item = text.substr(at, comma - at);
    char* end = nullptr;
    const double v = std::strtod(item.c_str(), &end);
    if (item.empty() || end != item.c_str() + item.size() || !std::isfinite(v))
      bad(flag, "a comma-separated list of numbers; got '" + text + "'");
    out.push_back(v);
    at = comma + 1;
  }
  return out;
}

std::vector<std::string> svg_paths(const std::string& prefix) {
  if (prefix.empty()) return {};
  return {prefix + "_lateness.svg", prefix + "_energy.svg", prefix + "_punctuality.svg"};
}

void write_days_csv(std::ostream& out, const std::vector<recovery::DayRecord>& days) {
  out << "day,arrivals,punctual,punctuality,mean_lateness_s,p95_lateness_s,max_lateness_s,"
         "recoveries,mean_recovery_time_s,unrecovered_episodes,primary_delays,tail_delays,"
         "knock_on_delays,takeovers,arrivals_taken_over,traction_kJ,regen_kJ,used_regen_kJ,"
         "substation_kJ\n";
  char buf[600];
  for (const recovery::DayRecord& r : days) {
    std::snprintf(
        buf, sizeof buf,
        "%llu,%lld,%lld,%.6f,%.4f,%.3f,%.3f,%lld,%.3f,%lld,%lld,%lld,%lld,%lld,%lld,%.3f,"
        "%.3f,%.3f,%.3f\n",
        static_cast<unsigned long long>(r.day), static_cast<long long>(r.arrivals),
        static_cast<long long>(r.punctual), r.punctuality(), r.mean_lateness_s(), r.p95_lateness_s,
        r.max_lateness_s, static_cast<long long>(r.recoveries),
        r.recoveries > 0 ? r.recovery_time_sum_s / static_cast<double>(r.recoveries) : 0.0,
        static_cast<long long>(r.unrecovered_episodes), static_cast<long long>(r.primary_delays),
        static_cast<long long>(r.tail_delays), static_cast<long long>(r.knock_on_delays),
        static_cast<long long>(r.takeovers), static_cast<long long>(r.arrivals_taken_over),
        r.traction_kJ, r.regen_kJ, r.used_regen_kJ, r.substation_kJ);
    out << buf;
  }
}

void write_plan_csv(std::ostream& out, const recovery::Plan& plan) {
  out << "train,station,arrival_s,departure_s,dwell_s\n";
  char buf[300];
  for (std::size_t k = 0; k < plan.trains.size(); ++k)
    for (std::size_t j = 0; j < plan.stations.size(); ++j) {
      const auto& t = plan.trains[k];
      std::snprintf(buf, sizeof buf, "%zu,%s,%.3f,%.3f,%.3f\n", k + 1, plan.stations[j].c_str(),
                    t.arrival_s[j], t.departure_s[j], t.departure_s[j] - t.arrival_s[j]);
      out << buf;
    }
}

nlohmann::json estimate_brief(const recovery::Estimate& e) {
  return {{"mean", e.mean}, {"ci95", e.ci95}};
}

// Outputs of a run or a merge: the JSON, the per-day CSV and the three plots.
void add_run_outputs(data::OutputBatch& batch, const recovery::MonteCarloRun& run,
                     const std::string& shard, const MonteCarloArgs& a) {
  if (!a.json.empty()) {
    const nlohmann::json j = recovery::run_json(run, shard);
    batch.add(a.json, [j](std::ostream& o) { o << j.dump(1) << "\n"; });
  }
  if (!a.csv.empty()) batch.add(a.csv, [&run](std::ostream& o) { write_days_csv(o, run.days); });
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
  for (std::size_t i = 1; i < s.station_arrivals.size() && i < run.stations.size(); ++i) {
    names.push_back(run.stations[i]);
    punct.push_back(s.station_arrivals[i] > 0 ? static_cast<double>(s.station_punctual[i]) /
                                                    static_cast<double>(s.station_arrivals[i])
                                              : 1.0);
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

// Refuses a run whose day records would not fit in memory, before anything is allocated.
void check_day_memory(std::uint64_t days, std::size_t stations) {
  const double need =
      static_cast<double>(days) * static_cast<double>(recovery::day_memory_bytes(stations));
  const double have =
      static_cast<double>(sysconf(_SC_PHYS_PAGES)) * static_cast<double>(sysconf(_SC_PAGE_SIZE));
  if (have > 0.0 && need > 0.5 * have) {
    char buf[300];
    std::snprintf(buf, sizeof buf,
                  "at most half the memory for the day records: %llu days need about %.1f GB, "
                  "the machine has %.1f GB; run them in shards (--shard i/N) and merge",
                  static_cast<unsigned long long>(days), need / 1e9, have / 1e9);
    bad("--days", buf);
  }
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
  const recovery::MonteCarloStatistics s = recovery::summarise(run.days, run.histogram);
  recovery::MonteCarloSummary sm;
  sm.termination = dp::Termination::CONVERGENCE;
  sm.first_day = 0;
  sm.last_day = run.days.size();
  sm.statistics = s;
  sm.plan_substation_kJ = run.plan_energy.value("substation_kJ", 0.0);
  sm.plan_traction_kJ = run.plan_energy.value("traction_kJ", 0.0);
  std::FILE* out = a.json == "-" || a.csv == "-" ? stderr : stdout;
  std::fprintf(out, "merged %zu shards: ", shards.size());
  std::fputs(sm.BriefReport().c_str(), out);
  data::OutputBatch batch;
  add_run_outputs(batch, run, "", a);
  batch.commit();
}

void run_montecarlo(const MonteCarloArgs& a) {
  if (a.reference == !a.plan_file.empty()) bad("--plan/--reference", "exactly one of them");
  if (a.days < 1 || a.days > 100000000) bad("--days", "a number of days from 1 to 1e8");
  if (a.seed < 0) bad("--seed", "a seed >= 0");
  recovery::MonteCarloOptions o;
  if (a.recovery == "exact")
    o.recovery = recovery::RecoveryPolicy::Exact;
  else if (a.recovery == "rule")
    o.recovery = recovery::RecoveryPolicy::Rule;
  else if (a.recovery == "exact-punctual")
    o.recovery = recovery::RecoveryPolicy::ExactPunctual;
  else
    bad("--recovery", "exact, exact-punctual or rule; got '" + a.recovery + "'");
  std::string why;
  if (!recovery::parse_delay_tail(a.tail, o.delays, &why)) bad("--tail", why);
  o.seed = static_cast<std::uint64_t>(a.seed);
  o.early_s = a.early_s;
  o.run_early_s = a.run_early_s;
  o.min_dwell_s = a.min_dwell_s;
  o.takeover_s = a.takeover_s;
  o.punctual_s = a.punctual_s;
  o.separation_s = a.separation_s;
  o.knot_step_s = a.knot_step_s;
  o.bin_step_s = a.step_s;
  require_valid(o);
  if (!(a.frontier_span_s >= 10.0 && a.frontier_span_s <= 600.0))
    bad("--frontier-span", "a span in [10, 600] s");
  std::pair<int, int> shard{1, 1};
  if (!a.shard.empty()) shard = parse_shard(a.shard);
  if (a.adjust && !a.shard.empty()) bad("--shard", "no shards with --adjust");
  recovery::PlanAdjustmentOptions adj;
  if (a.adjust) {
    if (a.adjusted_csv.empty()) bad("--adjusted-csv", "the file the adjusted plan goes to");
    adj.thetas = parse_list(a.thetas, "--thetas");
    adj.extra_dwells_s = parse_list(a.extra_dwells, "--extra-dwells");
    adj.run_early_s = parse_list(a.run_early_values, "--run-early-values");
    for (double b : adj.run_early_s)
      if (!(b >= 0.0 && b <= a.early_s))
        bad("--run-early-values", "offsets within [0, --early]; got '" + a.run_early_values + "'");
    if (a.run_early_s != 0.0) bad("--run-early", "--run-early-values with --adjust");
    adj.target_punctuality = a.target;
    adj.search_days = static_cast<std::uint64_t>(std::max(0LL, a.search_days));
    adj.threads = a.problem.threads;
    require_valid(adj);
  } else if (!a.adjusted_csv.empty()) {
    bad("--adjusted-csv", "only with --adjust");
  }
  check_targets(a, a.adjust);
  const Problem p = load_fleet_problem(a.problem, "--train-file");
  PlanStops ps = read_plan_stops(p.line, a.reference, a.plan_file);
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
  if (a.reference) plan = reference_plan_on(library, stops);
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
    nlohmann::json cands = nlohmann::json::array();
    for (std::size_t i = 0; i < r.candidates.size(); ++i) {
      const auto& c = r.candidates[i];
      const auto& s = c.statistics;
      std::fprintf(out, "%s %5.2f %6.1f %6.1f %10.5f %10.5f %10.3f %8.2f %16.1f %16.1f %16.1f\n",
                   i == r.summary.chosen ? "*" : " ", c.theta, c.extra_dwell_s, c.run_early_s,
                   s.punctuality.mean, s.punctuality.ci95, s.mean_lateness_s.mean,
                   s.p95_lateness_s.mean, s.substation_kJ.mean, s.substation_kJ.ci95,
                   c.plan_substation_kJ);
      cands.push_back({{"theta", c.theta},
                       {"extra_dwell_s", c.extra_dwell_s},
                       {"run_early_s", c.run_early_s},
                       {"running_times_s", c.running_times_s},
                       {"dwells_s", c.dwells_s},
                       {"meets_target", c.meets_target},
                       {"plan_traction_kJ", c.plan_traction_kJ},
                       {"plan_substation_kJ", c.plan_substation_kJ},
                       {"punctuality", estimate_brief(s.punctuality)},
                       {"mean_lateness_s", estimate_brief(s.mean_lateness_s)},
                       {"p95_lateness_s", estimate_brief(s.p95_lateness_s)},
                       {"recovery_time_s", estimate_brief(s.recovery_time_s)},
                       {"traction_kJ", estimate_brief(s.traction_kJ)},
                       {"substation_kJ", estimate_brief(s.substation_kJ)}});
    }
    const nlohmann::json j = {{"plan", plan_name},
                              {"seed", a.seed},
                              {"search_days", a.search_days},
                              {"target_punctuality", a.target},
                              {"target_met", r.summary.target_met},
                              {"chosen", r.summary.chosen},
                              {"chosen_run_early_s", r.chosen().run_early_s},
                              {"candidates", cands},
                              {"warnings", r.summary.warnings},
                              {"brief_report", r.summary.BriefReport()}};
    data::OutputBatch batch;
    const recovery::Plan chosen = r.chosen().plan;
    batch.add(a.adjusted_csv, [&chosen](std::ostream& o) { write_plan_csv(o, chosen); });
    if (!a.json.empty()) batch.add(a.json, [&j](std::ostream& o) { o << j.dump(1) << "\n"; });
    batch.commit();
    return;
  }
  const auto [first, last] =
      recovery::shard_days(static_cast<std::uint64_t>(a.days), shard.first, shard.second);
  const recovery::DayRecord plan_day = mc->plan_day();
  progress.update("day", 0, static_cast<int>(last - first));
  std::vector<recovery::DayRecord> days = mc->run_days(
      first, last, a.problem.threads,
      std::function<void(int, int)>([&](int d, int t) { progress.update("day", d, t); }));
  recovery::MonteCarloRun run;
  run.stations = plan.stations;
  run.histogram = recovery::pooled_histogram(days);
  run.days = std::move(days);
  run.plan_energy = {{"traction_kJ", plan_day.traction_kJ},
                     {"substation_kJ", plan_day.substation_kJ},
                     {"used_regen_kJ", plan_day.used_regen_kJ},
                     {"regen_kJ", plan_day.regen_kJ}};
  run.config = {{"plan", plan_name},
                {"trains", plan.trains.size()},
                {"days", a.days},
                {"seed", a.seed},
                {"recovery", a.recovery},
                {"p_none", o.delays.p_none},
                {"p_small", o.delays.p_small},
                {"small_max_s", o.delays.small_max_s},
                {"tail", o.delays.tail_text()},
                {"early_s", o.early_s},
                {"run_early_s", o.run_early_s},
                {"min_dwell_s", o.min_dwell_s},
                {"takeover_s", o.takeover_s},
                {"punctual_s", o.punctual_s},
                {"on_time_tolerance_s", o.on_time_tolerance_s},
                {"separation_s", mc->separation_s()},
                {"knot_step_s", o.knot_step_s},
                {"bin_step_s", o.bin_step_s},
                {"frontier_span_s", a.frontier_span_s},
                {"ds_m", a.problem.ds_m},
                {"dv_kmh", a.problem.dv_kmh},
                {"line_checksum", std::to_string(p.line.checksum())},
                {"train_checksum", std::to_string(data::train_checksum(p.train))}};
  recovery::MonteCarloSummary sm;
  sm.termination = dp::Termination::CONVERGENCE;
  sm.first_day = first;
  sm.last_day = last;
  sm.threads = a.problem.threads;
  sm.separation_s = mc->separation_s();
  sm.section_runs = runs->piece_count();
  sm.statistics = recovery::summarise(run.days, run.histogram);
  sm.plan_traction_kJ = plan_day.traction_kJ;
  sm.plan_substation_kJ = plan_day.substation_kJ;
  sm.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
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
  add_plan_source_options(cmd, args->plan_file, args->reference);
  cmd->add_option("--days", args->days, "simulated days")->capture_default_str();
  cmd->add_option("--seed", args->seed, "seed of the delay draws")->capture_default_str();
  cmd->add_option("--recovery", args->recovery,
                  "exact (question 3.1's policy, early running allowed), exact-punctual (the same, "
                  "every arrival on the way punctual where flat out can make it) or rule (flat "
                  "out until on time)")
      ->capture_default_str();
  cmd->add_option("--tail", args->tail,
                  "delays over 10 s: exponential:MEAN (10 s + exponential) or uniform:LOW:HIGH")
      ->capture_default_str();
  cmd->add_option("--early", args->early_s, "trains may arrive and depart this early (s)")
      ->capture_default_str();
  cmd->add_option("--run-early", args->run_early_s,
                  "run the plan this much ahead of the timetable, within --early (s)")
      ->capture_default_str();
  cmd->add_option("--run-early-values", args->run_early_values,
                  "operating offsets searched by --adjust (s)")
      ->capture_default_str();
  cmd->add_option("--min-dwell", args->min_dwell_s, "shortest dwell at a stop (s)")
      ->capture_default_str();
  cmd->add_option("--takeover", args->takeover_s,
                  "a delay over this is not recovered: the next service takes over (s)")
      ->capture_default_str();
  cmd->add_option("--punctual", args->punctual_s, "an arrival this late is still punctual (s)")
      ->capture_default_str();
  cmd->add_option("--separation", args->separation_s,
                  "least time between departures from a station (s; default: from the cap)");
  cmd->add_option("--knot-step", args->knot_step_s,
                  "section runs precomputed every this many seconds of running time")
      ->capture_default_str();
  cmd->add_option("--step", args->step_s, "power-flow time step (s, divides 1 s)")
      ->capture_default_str();
  cmd->add_option("--shard", args->shard, "simulate slice i of N of the days (i/N)");
  cmd->add_flag("--adjust", args->adjust,
                "search the plan family for the least substation energy at the punctuality "
                "target");
  cmd->add_option("--target", args->target, "punctuality target of --adjust (share)")
      ->capture_default_str();
  cmd->add_option("--search-days", args->search_days, "days per candidate plan of --adjust")
      ->capture_default_str();
  cmd->add_option("--thetas", args->thetas,
                  "margin mixes searched by --adjust (0: optimal split, "
                  "1: equal margins)")
      ->capture_default_str();
  cmd->add_option("--extra-dwells", args->extra_dwells, "extra dwells searched by --adjust (s)")
      ->capture_default_str();
  cmd->add_option("--adjusted-csv", args->adjusted_csv, "write the adjusted plan (timetable CSV)");
  add_plan_engine_options(cmd, args->problem, args->frontier_span_s, args->cache_dir,
                          args->no_cache);
  cmd->add_flag("--quiet", args->quiet, "no progress line on stderr");
  cmd->add_flag("--full-report", args->full_report, "print the full report");
  cmd->add_option("--json", args->json, "write the statistics and every day's record (JSON)");
  cmd->add_option("--csv", args->csv, "write one row per day (CSV)");
  cmd->add_option("--svg-prefix", args->svg_prefix,
                  "write P_lateness.svg, P_energy.svg and P_punctuality.svg");
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
