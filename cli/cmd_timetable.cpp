// `ecorail timetable evaluate|optimise`: fleet timetables that use regenerated braking energy
// (question 2.1). Parses flags into the timetable room's problem and options, prints its
// summaries and hands its results to the output writers; the computing is in timetable/.
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "cli/commands.hpp"
#include "cli/output_options.hpp"
#include "cli/problem_options.hpp"
#include "data/atomic_file.hpp"
#include "data/csv_reader.hpp"
#include "data/input_error.hpp"
#include "data/route_builder.hpp"
#include "dp/section_library.hpp"
#include "output/fleet_outputs.hpp"
#include "timetable/fleet_models.hpp"
#include "timetable/fleet_pattern.hpp"
#include "timetable/headway_optimiser.hpp"
#include "timetable/pattern_search.hpp"

namespace ecorail::cli {

namespace {

struct TimetableArgs {
  ProblemOptions problem;
  int trains = 100;
  int span_s = 63900;
  std::string headway = "120:660";
  double trip_time_s = 2086.0;
  std::string dwell_range = "30:45";
  double dwell_s = 30.0;
  std::string model = "power-flow";
  std::string overlap = "ahead";
  double step_s = 0.01;
  std::vector<double> sections_at_m;
  std::string headways_file, departures_file;
  bool uniform = false;
  std::uint64_t seed = 1;
  double time_limit_s = 0.0;
  int restarts = 2;
  long moves = 2000000;
  double anneal_step_s = 1.0;
  std::string optimise = "headways";
  std::string json, csv, xlsx, diagram, power_plot;
  std::string window = "0:7200";
  bool quiet = false;
  bool full_report = false;
};

[[noreturn]] void bad(const std::string& flag, const std::string& expected) {
  throw data::InputError("command line", 0, flag, expected);
}

// "A:B" as two numbers, A <= B.
std::pair<double, double> parse_range(const std::string& text, const std::string& flag) {
  const auto colon = text.find(':');
  if (colon == std::string::npos) bad(flag, "a range MIN:MAX; got '" + text + "'");
  const double a = data::parse_number(text.substr(0, colon), "command line", 0, flag);
  const double b = data::parse_number(text.substr(colon + 1), "command line", 0, flag);
  if (a > b) bad(flag, "MIN <= MAX in MIN:MAX; got '" + text + "'");
  return {a, b};
}

int whole_seconds(double v, const std::string& flag) {
  if (v != std::floor(v) || std::fabs(v) > 1e9)
    bad(flag, "whole seconds; got " + data::format_number(v));
  return static_cast<int>(v);
}

timetable::FleetProblem fleet_problem(const TimetableArgs& a) {
  timetable::FleetProblem p;
  p.trains = a.trains;
  p.span_s = a.span_s;
  const auto [hmin, hmax] = parse_range(a.headway, "--headway");
  p.headway_min_s = whole_seconds(hmin, "--headway");
  p.headway_max_s = whole_seconds(hmax, "--headway");
  p.trip_time_s = a.trip_time_s;
  std::tie(p.dwell_min_s, p.dwell_max_s) = parse_range(a.dwell_range, "--dwell-range");
  std::string why;
  if (!p.IsValid(&why)) bad("--trains/--span/--headway/--trip-time/--dwell-range", why);
  if (!(a.dwell_s >= p.dwell_min_s && a.dwell_s <= p.dwell_max_s))
    bad("--dwell", "a dwell within --dwell-range " + a.dwell_range + " s; got " +
                       data::format_number(a.dwell_s));
  return p;
}

timetable::EnergyModelOptions model_options(const TimetableArgs& a) {
  timetable::EnergyModelOptions o;
  const auto model = timetable::model_from_name(a.model);
  if (!model) bad("--model", "power-flow, overlap or sections; got '" + a.model + "'");
  o.model = *model;
  const auto variant = timetable::overlap_variant_from_name(a.overlap);
  if (!variant) bad("--overlap", "ahead or either; got '" + a.overlap + "'");
  o.overlap = *variant;
  o.time_step_s = a.step_s;
  o.section_boundaries_m = a.sections_at_m;
  if (o.model == timetable::EnergyModel::Sections && o.section_boundaries_m.empty())
    bad("--sections-at",
        "at least one supply-section boundary (m from the first station) for "
        "--model sections");
  std::string why;
  if (!o.IsValid(&why)) bad("--step/--sections-at", why);
  return o;
}

// Departures from --headways FILE (column headway_s), --departures FILE (column departure_s) or
// uniform; each value a whole number of seconds.
std::vector<int> read_departures(const TimetableArgs& a, const timetable::FleetProblem& p) {
  if (!a.headways_file.empty() && !a.departures_file.empty())
    bad("--headways", "either --headways or --departures, not both");
  if (a.uniform && (!a.headways_file.empty() || !a.departures_file.empty()))
    bad("--uniform", "--uniform alone, without --headways or --departures");
  const bool headways = !a.headways_file.empty();
  const std::string file = headways ? a.headways_file : a.departures_file;
  if (file.empty()) return timetable::departures_from_headways(timetable::uniform_headways(p));
  const auto table = data::CsvTable::read(file);
  const std::string column = headways ? "headway_s" : "departure_s";
  const std::size_t c = table.column(column);
  std::vector<int> values;
  for (const auto& row : table.rows()) {
    const double v = table.number(row, c);
    if (v != std::floor(v) || v < 0 || v > 1e9)
      throw data::InputError(file, row.row, column, "a whole number of seconds >= 0");
    if (headways && (v < p.headway_min_s || v > p.headway_max_s))
      throw data::InputError(file, row.row, column,
                             "a headway in [" + std::to_string(p.headway_min_s) + ", " +
                                 std::to_string(p.headway_max_s) + "] s; got " +
                                 data::format_number(v));
    values.push_back(static_cast<int>(v));
  }
  const std::vector<int> t = headways ? timetable::departures_from_headways(values) : values;
  const std::string why = timetable::departures_problem(p, t);
  if (!why.empty())
    throw data::InputError(file, 0, column, "departures that keep the problem: " + why);
  return t;
}

void add_fleet_options(CLI::App* cmd, TimetableArgs& a) {
  add_problem_options(cmd, a.problem, false);
  cmd->add_option("--trains", a.trains, "number of trains")->capture_default_str();
  cmd->add_option("--span", a.span_s, "first to last departure (s)")->capture_default_str();
  cmd->add_option("--headway", a.headway, "headway range MIN:MAX (whole s)")->capture_default_str();
  cmd->add_option("--trip-time", a.trip_time_s, "trip time incl. dwells (s)")
      ->capture_default_str();
  cmd->add_option("--dwell-range", a.dwell_range, "dwell range MIN:MAX (s)")->capture_default_str();
  cmd->add_option("--dwell", a.dwell_s, "the pattern's dwell at every stop (s)")
      ->capture_default_str();
  cmd->add_option("--model", a.model, "power-flow, overlap or sections")->capture_default_str();
  cmd->add_option("--overlap", a.overlap, "overlap model: ahead (contest) or either neighbour")
      ->capture_default_str();
  cmd->add_option("--step", a.step_s, "time step of the power balance (s, divides 1 s)")
      ->capture_default_str();
  cmd->add_option("--sections-at", a.sections_at_m,
                  "supply-section boundaries, m from the first station (sections model)")
      ->delimiter(',');
  cmd->add_option("--json", a.json, "energy breakdown (JSON)");
  cmd->add_option("--csv", a.csv, "timetable: train, station, arrival, departure (CSV)");
  cmd->add_option("--xlsx", a.xlsx, "timetable and energy (XLSX)");
  cmd->add_option("--diagram", a.diagram, "train diagram (.svg or .png)");
  cmd->add_option("--power-plot", a.power_plot, "power over --window (.svg or .png)");
  cmd->add_option("--window", a.window, "clock window FROM:TO (s) of the plots")
      ->capture_default_str();
  cmd->add_flag("--quiet", a.quiet, "no progress on stderr");
  cmd->add_flag("--full-report", a.full_report, "print the solver's full report");
}

void print_energy(const timetable::FleetEvaluation& ev, const char* what) {
  std::printf(
      "%s (%s%s%s): substation %.1f kJ = traction %.1f kJ - used regen %.1f kJ (of %.1f kJ "
      "regenerated, %.2f %%)\n",
      what, std::string(timetable::model_name(ev.model)).c_str(),
      ev.model == timetable::EnergyModel::Overlap
          ? (", " + std::string(timetable::overlap_variant_name(ev.overlap))).c_str()
          : "",
      ev.model == timetable::EnergyModel::Overlap
          ? ""
          : (", step " + data::format_number(ev.time_step_s) + " s").c_str(),
      ev.total.substation_J() / 1e3, ev.total.traction_J / 1e3, ev.total.used_regen_J / 1e3,
      ev.total.regen_J / 1e3,
      ev.total.regen_J > 0 ? 100.0 * ev.total.used_regen_J / ev.total.regen_J : 0.0);
}

// Everything both subcommands share: the line's sections, the pattern and its models.
struct FleetSetup {
  timetable::FleetProblem problem;
  timetable::EnergyModelOptions model;
  std::vector<std::string> stops;
  std::vector<double> positions_m;
  std::unique_ptr<dp::SectionLibrary> library;  // kept for pattern optimisation
  timetable::PatternTrip pattern;
  std::unique_ptr<timetable::FleetModels> models;
};

FleetSetup setup(const TimetableArgs& a) {
  FleetSetup s;
  s.problem = fleet_problem(a);
  s.model = model_options(a);
  check_output_targets({{"--json", a.json, false},
                        {"--csv", a.csv, false},
                        {"--xlsx", a.xlsx, false},
                        {"--diagram", a.diagram, true},
                        {"--power-plot", a.power_plot, true}});
  ProblemOptions whole = a.problem;
  whole.from.clear();
  const Problem p = load_problem(whole);
  const std::string from = a.problem.from.empty() ? p.line.stations.front().name : a.problem.from;
  const std::string to = a.problem.to.empty() ? p.line.stations.back().name : a.problem.to;
  s.stops = data::stops_between(p.line, from, to);
  if (s.stops.size() < 2) bad("--to", "a station other than --from");
  dp::SectionLibraryOptions lib_options;
  lib_options.engine = engine_options(a.problem);
  s.library = std::make_unique<dp::SectionLibrary>(
      p.train, data::build_routes(p.line, s.stops, p.train), lib_options);
  const dp::SectionLibrary& library = *s.library;
  const std::vector<double> dwells(s.stops.size() - 2, a.dwell_s);
  dp::JourneyOptions journey;
  journey.engine = lib_options.engine;
  journey.measure_marginals = false;
  try {
    s.pattern = timetable::optimal_split_pattern(library, dwells, s.problem.trip_time_s, journey);
  } catch (const dp::InfeasibleTimeError& e) {
    bad("--trip-time", "a trip time that leaves at least the flat-out running time of " +
                           data::format_number(e.minimum_s()) + " s after the dwells");
  }
  double pos = 0.0;
  s.positions_m.push_back(0.0);
  for (std::size_t i = 0; i < library.size(); ++i)
    s.positions_m.push_back(pos += library.route(i).length_m());
  s.models = std::make_unique<timetable::FleetModels>(s.pattern.trip, s.problem, s.model);
  return s;
}

void write_fleet_outputs(const TimetableArgs& a, const FleetSetup& s,
                         const timetable::FleetEvaluation& ev, nlohmann::json energy) {
  output::FleetTimetable tt{s.stops, s.positions_m, ev.departures_s, s.pattern.trip};
  energy["pattern"] = {{"dwells_s", s.pattern.pattern.dwells_s},
                       {"running_times_s", s.pattern.pattern.running_times_s},
                       {"trip_time_s", s.pattern.pattern.trip_time_s()}};
  energy["stations"] = s.stops;
  const auto [w0, w1] = parse_range(a.window, "--window");
  data::OutputBatch batch;
  if (!a.json.empty()) batch.add(a.json, [&](std::ostream& o) { o << energy.dump(2) << "\n"; });
  if (!a.csv.empty())
    batch.add(a.csv, [&](std::ostream& o) { output::write_timetable_csv(o, tt); });
  if (!a.xlsx.empty())
    batch.add_produced(a.xlsx, [&](const std::filesystem::path& f) {
      output::write_timetable_xlsx(f, tt, energy);
    });
  const std::string model = energy.value("model", "");
  if (!a.diagram.empty())
    batch.add_produced(a.diagram, [&](const std::filesystem::path& f) {
      output::write_train_diagram(f, *output::plot_format_for(a.diagram), tt, w0, w1,
                                  "Train diagram, " + std::to_string(ev.departures_s.size()) +
                                      " trains (" + model + " model)");
    });
  if (!a.power_plot.empty()) {
    if (ev.model == timetable::EnergyModel::Overlap)
      bad("--power-plot", "a power-flow or sections model (the overlap model has no power trace)");
    auto balance = s.models->make_balance();
    balance->place_all(ev.departures_s);
    const auto trace = balance->trace(w0, w1);
    batch.add_produced(a.power_plot, [&](const std::filesystem::path& f) {
      output::write_power_plot(f, *output::plot_format_for(a.power_plot), trace,
                               "Fleet power (" + model + " model)");
    });
  }
  batch.commit();
}

void run_evaluate(const TimetableArgs& a) {
  // The departures are checked before the line's sections are built: a bad file fails fast.
  const std::vector<int> departures = read_departures(a, fleet_problem(a));
  FleetSetup s = setup(a);
  const timetable::FleetEvaluation ev = s.models->evaluate(departures);
  print_energy(ev, "timetable evaluate");
  nlohmann::json energy = output::fleet_energy_json(ev, s.problem);
  write_fleet_outputs(a, s, ev, energy);
}

void run_optimise(const TimetableArgs& a) {
  FleetSetup s = setup(a);
  timetable::HeadwayOptimiserOptions o;
  o.seed = a.seed;
  o.time_limit_s = a.time_limit_s;
  o.restarts = a.restarts;
  o.moves_per_run = a.moves;
  o.anneal_step_s = a.anneal_step_s;
  o.threads = a.problem.threads;
  std::string why;
  if (!o.IsValid(&why)) bad("--restarts/--moves/--time-limit/--threads", why);
  if (!a.quiet && isatty(STDERR_FILENO)) {
    o.progress = [](const timetable::OptimiserProgress& p) {
      std::fprintf(stderr, "\r  %-26s best used %.1f kJ%s, %.1f s   ", p.stage.c_str(),
                   p.best_used_J / 1e3,
                   std::isfinite(p.bound_used_J)
                       ? (", bound " + std::to_string(p.bound_used_J / 1e3) + " kJ").c_str()
                       : "",
                   p.elapsed_s);
      std::fflush(stderr);
    };
  }
  if (a.optimise != "headways" && a.optimise != "pattern")
    bad("--optimise", "headways or pattern; got '" + a.optimise + "'");
  timetable::HeadwayOptimiserResult result;
  nlohmann::json pattern_report;
  if (a.optimise == "pattern") {
    timetable::PatternSearchOptions po;
    po.headways = o;
    const timetable::PatternSearchResult r =
        timetable::optimise_pattern(*s.library, s.problem, s.model, s.pattern, po);
    if (o.progress) std::fprintf(stderr, "\n");
    print_energy(r.headways_only, "headways alone, default pattern");
    std::printf("  %s\n", r.BriefReport().c_str());
    const auto& before = r.headways_only.total;
    const auto& after = r.timetable.evaluation.total;
    pattern_report = {{"moves_accepted", r.moves_accepted},
                      {"patterns_evaluated", r.patterns_evaluated},
                      {"headways_only_substation_energy_kJ", before.substation_J() / 1e3},
                      {"headways_only_traction_energy_kJ", before.traction_J / 1e3},
                      {"headways_only_used_regen_kJ", before.used_regen_J / 1e3},
                      {"retiming_saving_kJ", (before.substation_J() - after.substation_J()) / 1e3},
                      {"retiming_traction_cost_kJ", (after.traction_J - before.traction_J) / 1e3}};
    s.pattern = r.pattern;
    s.models = std::make_unique<timetable::FleetModels>(s.pattern.trip, s.problem, s.model);
    result = r.timetable;
  } else {
    result = timetable::optimise_headways(*s.models, o);
    if (o.progress) std::fprintf(stderr, "\n");
  }
  print_energy(result.evaluation, "timetable optimise");
  std::printf("  %s\n", result.summary.BriefReport().c_str());
  if (a.full_report) std::printf("%s", result.summary.FullReport().c_str());
  if (!result.summary.IsSolutionUsable())
    throw std::runtime_error("the optimiser failed: " + result.summary.message);
  nlohmann::json energy = output::fleet_energy_json(result.evaluation, s.problem);
  const auto& sm = result.summary;
  if (std::isfinite(sm.bound_used_regen_J)) {
    energy["bound_used_regen_kJ"] = sm.bound_used_regen_J / 1e3;
    energy["gap_fraction_of_substation"] = sm.gap_fraction;
    if (sm.pair_sum_J > 0.0) energy["pair_sum_of_result_kJ"] = sm.pair_sum_J / 1e3;
  }
  energy["summary"] = {{"termination", std::string(timetable::termination_name(sm.termination))},
                       {"method", sm.method},
                       {"exact", sm.exact},
                       {"seed", a.seed},
                       {"moves", sm.moves},
                       {"wall_s", sm.wall_s},
                       {"brief_report", sm.BriefReport()}};
  if (!pattern_report.is_null()) energy["pattern_search"] = pattern_report;
  write_fleet_outputs(a, s, result.evaluation, energy);
}

}  // namespace

void add_timetable_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("timetable", "fleet timetables that use regenerated energy");
  cmd->require_subcommand(1);
  static TimetableArgs eval_args, opt_args;
  auto* ev = cmd->add_subcommand("evaluate", "energy of a given timetable (default: uniform)");
  add_fleet_options(ev, eval_args);
  ev->add_option("--headways", eval_args.headways_file, "CSV with a column headway_s");
  ev->add_option("--departures", eval_args.departures_file, "CSV with a column departure_s");
  ev->add_flag("--uniform", eval_args.uniform, "uniform headways (the default)");
  ev->callback([] { run_evaluate(eval_args); });
  auto* op = cmd->add_subcommand("optimise", "headways that minimise the substation energy");
  add_fleet_options(op, opt_args);
  op->add_option("--seed", opt_args.seed, "random seed")->capture_default_str();
  op->add_option("--time-limit", opt_args.time_limit_s, "seconds (0: none)")->capture_default_str();
  op->add_option("--restarts", opt_args.restarts, "annealing runs per start")
      ->capture_default_str();
  op->add_option("--moves", opt_args.moves, "annealing moves per run")->capture_default_str();
  op->add_option("--anneal-step", opt_args.anneal_step_s, "time step of the annealing (s)")
      ->capture_default_str();
  op->add_option("--optimise", opt_args.optimise,
                 "headways (pattern fixed) or pattern (dwells and running times too)")
      ->capture_default_str();
  op->callback([] { run_optimise(opt_args); });
}

}  // namespace ecorail::cli
