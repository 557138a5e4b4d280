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
#include "cli/service_options.hpp"
#include "data/atomic_file.hpp"
#include "data/csv_reader.hpp"
#include "data/input_error.hpp"
#include "data/route_builder.hpp"
#include "dp/section_library.hpp"
#include "output/fleet_outputs.hpp"
#include "power/supply_loader.hpp"
#include "timetable/fleet_models.hpp"
#include "timetable/fleet_pattern.hpp"
#include "timetable/headway_optimiser.hpp"
#include "timetable/pattern_search.hpp"
#include "timetable/windowed_classes.hpp"

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
  bool per_train_patterns = false;
  bool window_bound = false;    // --window-bound (timetable/window_bound.hpp)
  bool optimise_given = false;  // --optimise on the command line (not its default)
  std::string json, csv, xlsx, diagram, power_plot;
  std::string window = "0:7200";
  std::vector<std::string> peaks;             // --peak FROM:TO, any number
  std::string peak_headway, offpeak_headway;  // "" : 120:150 and 300:660 with --peak
  std::string nearest;                        // evaluate --nearest PEAK:OFFPEAK
  bool quiet = false;
  bool full_report = false;
  ServiceArgs service;  // --separation, --profiles, ... (cli/service_options.hpp)
  // Network model (docs/power_network.md).
  std::string power_supply, voltage_plot;
  double voltage_at_s = 3600.0;
  CLI::Option* step_option = nullptr;  // whether --step was given (the network's default differs)
  OutputOptions gtfs;                  // --gtfs DIR, --gtfs-start (its other fields unused)
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
  if (a.peaks.empty() && !(a.peak_headway.empty() && a.offpeak_headway.empty()))
    bad("--peak-headway/--offpeak-headway", "at least one --peak FROM:TO window with them");
  for (const std::string& w : a.peaks) {
    const auto [from, to] = parse_range(w, "--peak");
    if (from == to) bad("--peak", "a window FROM:TO with FROM < TO; got '" + w + "'");
    p.peak_windows.push_back({whole_seconds(from, "--peak"), whole_seconds(to, "--peak")});
  }
  if (p.windowed()) {
    // With peak windows, --headway gives way to the two classes.
    const auto [pmin, pmax] =
        parse_range(a.peak_headway.empty() ? "120:150" : a.peak_headway, "--peak-headway");
    p.peak_headway_min_s = whole_seconds(pmin, "--peak-headway");
    p.peak_headway_max_s = whole_seconds(pmax, "--peak-headway");
    const auto [omin, omax] =
        parse_range(a.offpeak_headway.empty() ? "300:660" : a.offpeak_headway, "--offpeak-headway");
    p.headway_min_s = whole_seconds(omin, "--offpeak-headway");
    p.headway_max_s = whole_seconds(omax, "--offpeak-headway");
  }
  std::string why;
  if (!p.IsValid(&why))
    bad(p.windowed() ? "--trains/--span/--peak/--peak-headway/--offpeak-headway"
                     : "--trains/--span/--headway/--trip-time/--dwell-range",
        why);
  if (!(a.dwell_s >= p.dwell_min_s && a.dwell_s <= p.dwell_max_s))
    bad("--dwell", "a dwell within --dwell-range " + a.dwell_range + " s; got " +
                       data::format_number(a.dwell_s));
  return p;
}

timetable::EnergyModelOptions model_options(const TimetableArgs& a) {
  timetable::EnergyModelOptions o;
  const auto model = timetable::model_from_name(a.model);
  if (!model) bad("--model", "power-flow, overlap, sections or network; got '" + a.model + "'");
  o.model = *model;
  const auto variant = timetable::overlap_variant_from_name(a.overlap);
  if (!variant) bad("--overlap", "ahead or either; got '" + a.overlap + "'");
  o.overlap = *variant;
  o.time_step_s = a.step_s;
  o.section_boundaries_m = a.sections_at_m;
  if (o.model == timetable::EnergyModel::Network) {
    if (a.power_supply.empty())
      bad("--power-supply", "a power-supply file (TOML) for --model network");
    if (a.step_option == nullptr || a.step_option->count() == 0)
      o.time_step_s = timetable::kNetworkTimeStep_s;
    o.power_supply =
        std::make_shared<const power::PowerSupply>(power::load_power_supply(a.power_supply));
  } else if (!a.power_supply.empty()) {
    bad("--power-supply", "--model network (the other models have no supply network)");
  }
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
  if (!a.nearest.empty()) {
    if (!file.empty() || a.uniform)
      bad("--nearest", "--nearest alone, without --headways, --departures or --uniform");
    if (!p.windowed()) bad("--nearest", "peak windows (--peak FROM:TO)");
    const auto [peak, off] = parse_range(a.nearest, "--nearest");
    return timetable::departures_from_headways(timetable::windowed_nearest_headways(p, peak, off));
  }
  if (file.empty()) return timetable::departures_from_headways(timetable::uniform_headways(p));
  const auto table = data::CsvTable::read(file);
  const std::string column = headways ? "headway_s" : "departure_s";
  const std::size_t c = table.column(column);
  std::vector<int> values;
  for (const auto& row : table.rows()) {
    const double v = table.number(row, c);
    if (v != std::floor(v) || v < 0 || v > 1e9)
      throw data::InputError(file, row.row, column, "a whole number of seconds >= 0");
    if (headways && !p.windowed() && (v < p.headway_min_s || v > p.headway_max_s))
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
  a.step_option =
      cmd->add_option("--step", a.step_s,
                      "time step of the power balance (s, divides 1 s; network: 0.1 by default)")
          ->capture_default_str();
  cmd->add_option("--sections-at", a.sections_at_m,
                  "supply-section boundaries, m from the first station (sections model)")
      ->delimiter(',');
  cmd->add_option("--json", a.json, "energy breakdown (JSON)");
  cmd->add_option("--csv", a.csv, "timetable: train, station, arrival, departure (CSV)");
  cmd->add_option("--xlsx", a.xlsx, "timetable and energy (XLSX)");
  cmd->add_option("--diagram", a.diagram, "train diagram (.svg or .png)");
  cmd->add_option("--power-plot", a.power_plot,
                  "power over --window (.svg or .png; network: each substation's)");
  cmd->add_option("--power-supply", a.power_supply,
                  "the line's traction power supply (TOML) for --model network");
  cmd->add_option("--voltage-plot", a.voltage_plot,
                  "network: the voltage along the line at --voltage-at (.svg or .png)");
  cmd->add_option("--voltage-at", a.voltage_at_s, "network: clock time (s) of --voltage-plot")
      ->capture_default_str();
  cmd->add_option("--window", a.window, "clock window FROM:TO (s) of the plots")
      ->capture_default_str();
  cmd->add_option("--peak", a.peaks,
                  "peak window FROM:TO (s on the timetable clock), repeatable; headways "
                  "overlapping one are peak headways");
  cmd->add_option("--peak-headway", a.peak_headway, "peak headway range MIN:MAX (default 120:150)");
  cmd->add_option("--offpeak-headway", a.offpeak_headway,
                  "off-peak headway range MIN:MAX with --peak (default 300:660)");
  cmd->add_flag("--quiet", a.quiet, "no progress on stderr");
  cmd->add_flag("--full-report", a.full_report, "print the solver's full report");
  add_service_options(cmd, a.service);
  add_gtfs_options(cmd, a.gtfs);
}

void print_energy(const timetable::FleetEvaluation& ev, const char* what) {
  if (ev.network) {
    const timetable::NetworkEvaluation& n = *ev.network;
    std::printf(
        "%s (network, step %s s): substations %.1f kJ + used regen %.1f kJ = traction input "
        "%.1f kJ + auxiliaries %.1f kJ + line losses %.1f kJ; regen curtailed %.1f kJ of %.1f "
        "kJ, traction curtailed %.1f kJ; train voltage %.1f to %.1f V\n",
        what, data::format_number(ev.time_step_s).c_str(), n.substation_J / 1e3,
        n.used_regen_J / 1e3, n.traction_input_J / 1e3, n.auxiliary_J / 1e3, n.line_losses_J / 1e3,
        n.curtailed_regen_J / 1e3, n.regen_J / 1e3, n.curtailed_traction_J / 1e3,
        n.min_train_voltage_V, n.max_train_voltage_V);
    return;
  }
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
  // Per-train patterns (optimise --per-train-patterns): train k's pattern and trip.
  std::vector<timetable::FleetPattern> per_train_patterns;
  std::vector<physics::Trip> per_train_trips;
  std::unique_ptr<timetable::FleetModels> models;
};

FleetSetup setup(const TimetableArgs& a) {
  FleetSetup s;
  s.problem = fleet_problem(a);
  s.model = model_options(a);
  std::vector<OutputTarget> targets = {{"--json", a.json, false},
                                       {"--csv", a.csv, false},
                                       {"--xlsx", a.xlsx, false},
                                       {"--diagram", a.diagram, true},
                                       {"--power-plot", a.power_plot, true},
                                       {"--voltage-plot", a.voltage_plot, true}};
  const std::vector<OutputTarget> gtfs = gtfs_targets(a.gtfs);
  targets.insert(targets.end(), gtfs.begin(), gtfs.end());  // no GTFS file is another's path
  check_output_targets(targets);
  check_service_args(a.service);
  if (!a.voltage_plot.empty() && s.model.model != timetable::EnergyModel::Network)
    bad("--voltage-plot", "--model network (only the network model has line voltages)");
  const Problem p = load_fleet_problem(a.problem);
  s.model.traction_efficiency = p.train.traction_efficiency;
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
  output::FleetTimetable tt{s.stops,        s.positions_m,          ev.departures_s,
                            s.pattern.trip, s.problem.peak_windows, s.per_train_trips};
  energy["pattern"] = {{"dwells_s", s.pattern.pattern.dwells_s},
                       {"running_times_s", s.pattern.pattern.running_times_s},
                       {"trip_time_s", s.pattern.pattern.trip_time_s()}};
  if (!s.per_train_patterns.empty()) {
    nlohmann::json patterns = nlohmann::json::array();
    for (std::size_t k = 0; k < s.per_train_patterns.size(); ++k) {
      const timetable::FleetPattern& p = s.per_train_patterns[k];
      patterns.push_back({{"train", k + 1},
                          {"dwells_s", p.dwells_s},
                          {"running_times_s", p.running_times_s},
                          {"trip_time_s", p.trip_time_s()}});
    }
    energy["patterns_per_train"] = patterns;
  }
  energy["stations"] = s.stops;
  if (ev.network) output::add_network_json(energy, *ev.network);
  const auto [w0, w1] = parse_range(a.window, "--window");
  data::OutputBatch batch;
  // The separation check first: it adds to the energy JSON (the batch writes on add).
  if (a.service.wanted() && !s.per_train_patterns.empty())
    bad("--separation", "one pattern for every train (not --per-train-patterns)");
  const auto service_run =
      run_service_check(a.service, *s.library, s.pattern.pattern, ev.departures_s, energy, batch);
  if (!a.json.empty()) batch.add(a.json, [&](std::ostream& o) { o << energy.dump(2) << "\n"; });
  if (!a.gtfs.gtfs.empty()) {
    // trip_id "train-001" ...: zero-padded so that the trips sort in departure order.
    const int width = static_cast<int>(std::to_string(ev.departures_s.size()).size());
    std::vector<std::pair<std::string, physics::Trip>> trips;
    for (std::size_t k = 0; k < ev.departures_s.size(); ++k) {
      std::string number = std::to_string(k + 1);
      number.insert(0, width - number.size(), '0');
      trips.emplace_back("train-" + number, tt.train_trip(k));
    }
    add_gtfs_outputs(batch, a.gtfs, trips);
  }
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
  if (!a.voltage_plot.empty()) {
    std::vector<int> ids;
    const auto flow =
        timetable::load_flow_at(s.models->network_setup(), ev.departures_s, a.voltage_at_s, &ids);
    batch.add_produced(a.voltage_plot, [&, flow, ids](const std::filesystem::path& f) {
      output::write_voltage_plot(f, *output::plot_format_for(a.voltage_plot), flow,
                                 *s.model.power_supply, ids,
                                 "Line voltage at " + output::clock_text(a.voltage_at_s) + " (" +
                                     data::format_number(a.voltage_at_s) + " s)");
    });
  }
  if (!a.power_plot.empty() && ev.network) {
    const auto trace =
        timetable::substation_trace(s.models->network_setup(), ev.departures_s, w0, w1);
    batch.add_produced(a.power_plot, [&, trace](const std::filesystem::path& f) {
      output::write_substation_plot(f, *output::plot_format_for(a.power_plot), trace,
                                    "Substation power (network model)");
    });
  } else if (!a.power_plot.empty()) {
    if (ev.model == timetable::EnergyModel::Overlap)
      bad("--power-plot", "a power-flow or sections model (the overlap model has no power trace)");
    // Per-train patterns: each train's own profile (kept alive here while the trace is made).
    std::vector<std::unique_ptr<timetable::PowerProfile>> own;
    std::vector<const timetable::PowerProfile*> profiles;
    for (const physics::Trip& trip : s.per_train_trips) {
      own.push_back(timetable::make_profile(trip, s.model));
      profiles.push_back(own.back().get());
    }
    auto balance = profiles.empty() ? s.models->make_balance() : s.models->make_balance(profiles);
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
  if (ev.network) {
    // The same day with every train burning its regenerated energy: what reuse saves.
    const auto off = timetable::evaluate_network(s.models->network_setup(), departures, false);
    energy["substation_energy_without_regen_kJ"] = off.substation_J / 1e3;
    energy["regen_saving_kJ"] = (off.substation_J - ev.network->substation_J) / 1e3;
    std::printf(
        "  without regeneration the substations would supply %.1f kJ: reuse saves %.1f kJ\n",
        off.substation_J / 1e3, (off.substation_J - ev.network->substation_J) / 1e3);
    if (ev.network->unsolved_instants > 0)
      throw std::runtime_error("the load flow found no solution at " +
                               std::to_string(ev.network->unsolved_instants) +
                               " instants; nothing written");
  }
  write_fleet_outputs(a, s, ev, energy);
}

void run_optimise(const TimetableArgs& given) {
  TimetableArgs a = given;
  if (a.per_train_patterns) {
    // Per-train patterns are a pattern optimisation: the flag implies --optimise pattern.
    if (a.optimise_given && a.optimise != "pattern")
      bad("--per-train-patterns", "--optimise pattern (per-train patterns re-time each train)");
    if (a.model != "power-flow" && a.model != "sections")
      bad("--per-train-patterns",
          "--model power-flow or sections (the per-train search prices one train's pattern "
          "against the fleet's power balance; the overlap model has none and the network "
          "balance lays one trip under every train); got '" +
              a.model + "'");
    a.optimise = "pattern";
  }
  FleetSetup s = setup(a);
  timetable::HeadwayOptimiserOptions o;
  o.seed = a.seed;
  o.time_limit_s = a.time_limit_s;
  o.restarts = a.restarts;
  o.moves_per_run = a.moves;
  o.anneal_step_s = a.anneal_step_s;
  o.threads = a.problem.threads;
  o.window_bound = a.window_bound;  // hook: timetable/window_bound.hpp
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
    po.per_train_patterns = a.per_train_patterns;
    po.time_limit_s = a.time_limit_s;
    po.threads = a.problem.threads;
    if (o.progress) {
      po.progress = [](const timetable::PatternProgress& p) {
        std::fprintf(stderr, "\r  %-26s %d moves of %d priced, substation %.1f kJ, %.1f s   ",
                     (p.stage + " moves").c_str(), p.moves_accepted, p.patterns_evaluated,
                     p.substation_J / 1e3, p.elapsed_s);
        std::fflush(stderr);
      };
    }
    const timetable::PatternSearchResult r =
        timetable::optimise_pattern(*s.library, s.problem, s.model, s.pattern, po);
    if (o.progress) std::fprintf(stderr, "\n");
    print_energy(r.headways_only, "headways alone, default pattern");
    std::printf("  %s\n", r.BriefReport().c_str());
    const auto& before = r.headways_only.total;
    const auto& after = r.timetable.evaluation.total;
    pattern_report = {
        {"moves_accepted", r.moves_accepted},
        {"patterns_evaluated", r.patterns_evaluated},
        {"headways_only_substation_energy_kJ", before.substation_J() / 1e3},
        {"headways_only_traction_energy_kJ", before.traction_J / 1e3},
        {"headways_only_used_regen_kJ", timetable::used_regen_of(r.headways_only) / 1e3},
        {"retiming_saving_kJ", (before.substation_J() - after.substation_J()) / 1e3},
        {"retiming_traction_cost_kJ", (after.traction_J - before.traction_J) / 1e3}};
    if (!r.per_train.empty()) {
      const auto& common = r.common_pattern.total;
      pattern_report["per_train_patterns"] = true;
      pattern_report["per_train_moves_accepted"] = r.per_train_moves_accepted;
      pattern_report["per_train_candidates_priced"] = r.per_train_candidates;
      pattern_report["common_pattern_substation_energy_kJ"] = common.substation_J() / 1e3;
      pattern_report["common_pattern_traction_energy_kJ"] = common.traction_J / 1e3;
      pattern_report["per_train_saving_kJ"] = (common.substation_J() - after.substation_J()) / 1e3;
      pattern_report["per_train_traction_cost_kJ"] = (after.traction_J - common.traction_J) / 1e3;
      pattern_report["per_train_stop"] = r.time_limit_reached   ? "time limit"
                                         : r.move_limit_reached ? "move limit"
                                                                : "local optimum";
      s.per_train_patterns = r.per_train;
      s.per_train_trips = r.per_train_trips;
    }
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
  if (std::isfinite(sm.bound_substation_J)) {
    // Network model: a lower bound on substation + curtailed traction energy.
    energy["bound_substation_kJ"] = sm.bound_substation_J / 1e3;
    energy["gap_fraction_of_substation"] = sm.gap_fraction;
  } else if (std::isfinite(sm.bound_used_regen_J)) {
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
  ev->add_option("--nearest", eval_args.nearest,
                 "with --peak: the timetable nearest (least squares) to class headways "
                 "PEAK:OFFPEAK (s), e.g. 149:331.5");
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
  op->add_flag("--window-bound", opt_args.window_bound,
               "also certify with the window bound (power-flow, one headway class; about a "
               "minute of CPU on the reference case)");
  op->add_flag("--per-train-patterns", opt_args.per_train_patterns,
               "each train its own dwells and running times (implies --optimise pattern; "
               "power-flow and sections models)");
  op->callback([op] {
    opt_args.optimise_given = op->get_option("--optimise")->count() > 0;
    run_optimise(opt_args);
  });
}

}  // namespace ecorail::cli
