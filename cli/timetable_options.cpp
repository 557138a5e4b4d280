#include "cli/timetable_options.hpp"

#include <cmath>

#include "data/csv_reader.hpp"
#include "data/input_error.hpp"
#include "data/route_builder.hpp"
#include "dp/resource_estimate.hpp"
#include "dp/time_target.hpp"
#include "energy/model_registry.hpp"
#include "fleet/windowed_classes.hpp"
#include "power/supply_loader.hpp"

namespace ecorail::cli {

namespace {

int whole_seconds(double v, const std::string& flag) {
  if (v != std::floor(v) || std::fabs(v) > 1e9)
    bad(flag, "whole seconds; got " + data::format_number(v));
  return static_cast<int>(v);
}

}  // namespace

std::pair<double, double> parse_range(const std::string& text, const std::string& flag) {
  const auto colon = text.find(':');
  if (colon == std::string::npos) bad(flag, "a range MIN:MAX; got '" + text + "'");
  const double a = data::parse_number(text.substr(0, colon), "command line", 0, flag);
  const double b = data::parse_number(text.substr(colon + 1), "command line", 0, flag);
  if (a > b) bad(flag, "MIN <= MAX in MIN:MAX; got '" + text + "'");
  return {a, b};
}

fleet::FleetProblem fleet_problem(const TimetableArgs& a) {
  fleet::FleetProblem p;
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

energy::EnergyModelOptions model_options(const TimetableArgs& a) {
  energy::EnergyModelOptions o;
  if (!energy::is_energy_model(a.model))
    bad("--model", energy::energy_model_names() + "; got '" + a.model + "'");
  o.model = a.model;
  const energy::ModelInputs reads = energy::model_inputs(a.model);
  const auto variant = energy::overlap_variant_from_name(a.overlap);
  if (!variant) bad("--overlap", "ahead or either; got '" + a.overlap + "'");
  o.overlap = *variant;
  const bool step_given = a.step_option != nullptr && a.step_option->count() > 0;
  o.time_step_s = step_given ? a.step_s : reads.default_time_step_s;
  o.section_boundaries_m = a.sections_at_m;
  // A flag the chosen model does not read is refused, never ignored (energy::ModelInputs).
  using energy::ModelInputs;
  auto refuse = [](const char* flag, bool ModelInputs::*input, const char* what) {
    bad(flag, "--model " + energy::models_with(input) + " (the other models have no " + what + ")");
  };
  const bool overlap_given = a.overlap_option != nullptr && a.overlap_option->count() > 0;
  if (overlap_given && !reads.overlap_variant)
    refuse("--overlap", &ModelInputs::overlap_variant, "overlap variant");
  if (!a.sections_at_m.empty() && !reads.section_boundaries)
    refuse("--sections-at", &ModelInputs::section_boundaries, "supply sections");
  if (reads.power_supply) {
    if (a.power_supply.empty())
      bad("--power-supply", "a power-supply file (TOML) for --model " + a.model);
    o.power_supply =
        std::make_shared<const power::PowerSupply>(power::load_power_supply(a.power_supply));
  } else if (!a.power_supply.empty()) {
    refuse("--power-supply", &ModelInputs::power_supply, "supply network");
  }
  if (!a.voltage_plot.empty() && !reads.power_supply)
    refuse("--voltage-plot", &ModelInputs::power_supply, "line voltages");
  if (reads.section_boundaries && o.section_boundaries_m.empty())
    bad("--sections-at",
        "at least one supply-section boundary (m from the first station) for --model " + a.model);
  // --separation is a flag: a value (--separation=-5) would silently read as "off".
  if (const CLI::Option* sep = a.service_separation)
    for (const std::string& r : sep->results())
      if (r != "true" && r != "1" && !r.empty())
        bad("--separation",
            "no value (a flag; --train-length, --braking set the check); got '" + r + "'");
  if (a.service_train_length != nullptr && a.service_train_length->count() > 0 &&
      !a.service.separation)
    bad("--train-length", "--separation (the train length is the separation check's)");
  std::string why;
  if (!o.IsValid(&why)) bad(reads.section_boundaries ? "--step/--sections-at" : "--step", why);
  return o;
}

std::vector<int> read_departures(const TimetableArgs& a, const fleet::FleetProblem& p) {
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
    return fleet::departures_from_headways(fleet::windowed_nearest_headways(p, peak, off));
  }
  if (file.empty()) return fleet::departures_from_headways(fleet::uniform_headways(p));
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
  const std::vector<int> t = headways ? fleet::departures_from_headways(values) : values;
  const std::string why = fleet::departures_problem(p, t);
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
  cmd->add_option("--model", a.model, energy::energy_model_names())->capture_default_str();
  a.overlap_option =
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
  a.service_train_length = cmd->get_option("--train-length");
  a.service_separation = cmd->get_option("--separation");
  add_gtfs_options(cmd, a.gtfs);
}

fleet::TimetableStudy make_study(const TimetableArgs& a) {
  fleet::TimetableStudySetup setup;
  setup.problem = fleet_problem(a);
  setup.model = model_options(a);
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
  Problem p = load_fleet_problem(a.problem);
  const std::string from = a.problem.from.empty() ? p.line.stations.front().name : a.problem.from;
  const std::string to = a.problem.to.empty() ? p.line.stations.back().name : a.problem.to;
  setup.stops = data::stops_between(p.line, from, to);
  if (setup.stops.size() < 2) bad("--to", "a station other than --from");
  check_gtfs_stops(a.gtfs, p.line, setup.stops);
  setup.line = std::move(p.line);
  setup.train = std::move(p.train);
  setup.engine = engine_options(a.problem);
  setup.dwell_s = a.dwell_s;
  try {
    return fleet::TimetableStudy(setup);
  } catch (const dp::InfeasibleTimeError& e) {
    bad("--trip-time", "a trip time that leaves at least the flat-out running time of " +
                           data::format_number(e.minimum_s()) + " s after the dwells");
  } catch (const dp::ResourceLimitError& e) {
    bad("--step", std::string("a grid that fits this machine: ") + e.what());
  } catch (const std::invalid_argument& e) {
    // Options that do not fit the run: a section boundary or the supply beyond its end.
    const std::string what = e.what();
    if (what.rfind("section_boundaries_m: ", 0) == 0) bad("--sections-at", what.substr(22));
    if (what.rfind("power_supply: ", 0) == 0)
      throw data::InputError(a.power_supply, 0, "position", what.substr(14));
    throw;
  }
}

}  // namespace ecorail::cli
