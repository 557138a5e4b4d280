#include "cli/problem_options.hpp"

#include <algorithm>
#include <filesystem>
#include <iostream>
#include <string>

#include "cli/output_options.hpp"
#include "data/csv_reader.hpp"
#include "data/input_error.hpp"
#include "data/line_loader.hpp"
#include "data/route_builder.hpp"
#include "data/train_io.hpp"
#include "data/ttobench_io.hpp"
#include "dp/threads.hpp"

namespace ecorail::cli {

namespace {
// The flags behind the engine options, checked first so a bad value names its flag (the
// options' own IsValid then guards the library's rules).
void check_grid_flags(const ProblemOptions& o) {
  if (!(o.ds_m > 0.0 && o.ds_m <= 100.0)) {
    throw data::InputError("command line", 0, "--ds", "a position step in (0, 100] m");
  }
  if (!(o.dv_kmh > 0.0 && o.dv_kmh <= 10.0)) {
    throw data::InputError("command line", 0, "--dv", "a speed step in (0, 10] km/h");
  }
  if (o.threads < 0 || o.threads > dp::kMaxThreads) {
    throw data::InputError("command line", 0, "--threads",
                           "0 (all cores) to " + std::to_string(dp::kMaxThreads) +
                               " threads (the bound on OpenMP threads); got " +
                               std::to_string(o.threads));
  }
}
}  // namespace

void add_problem_options(CLI::App* cmd, ProblemOptions& o, bool stations_required) {
  auto* from = cmd->add_option("--from", o.from, "departure station (e.g. A6)");
  auto* to = cmd->add_option("--to", o.to, "arrival station (e.g. A7)");
  if (stations_required) {
    from->required();
    to->required();
  }
  add_pass_through_option(cmd, o);
  cmd->add_option("--line", o.line_path,
                  "line: a directory of stations/gradients/speed_limits/curves CSVs, a TOML "
                  "file or a TTOBench track JSON (default: the embedded reference line)");
  cmd->add_option("--train", o.train_path,
                  "train TOML file or TTOBench train JSON (default: the reference train)");
  input_files(cmd, {"--line", "--train"});
  cmd->add_option("--curve-resistance", o.curve_resistance,
                  "curve resistance formula: 600/R, or roeckl (500/(R-30) from 300 m, "
                  "650/(R-55) below)")
      ->check(CLI::IsMember({std::string("600/R"), std::string("roeckl")}))
      ->capture_default_str();
  cmd->add_option("--ds", o.ds_m, "grid position step in m")->capture_default_str();
  cmd->add_option("--dv", o.dv_kmh, "grid speed step in km/h")->capture_default_str();
  cmd->add_option("--threads", o.threads, "OpenMP threads (default: all cores)");
  cmd->add_option("--objective", o.objective,
                  "traction: minimise traction energy; net: also credit regenerated energy")
      ->check(CLI::IsMember({std::string(dp::objective_name(dp::Objective::Traction)),
                             std::string(dp::objective_name(dp::Objective::Net))}))
      ->capture_default_str();
  cmd->add_option("--cruise", o.cruise,
                  "hold: a long cruise is driven as one speed hold with its coasting point "
                  "optimised (docs/journeys.md); grid: the grid's own cruise, as extracted")
      ->check(CLI::IsMember({std::string("hold"), std::string("grid")}))
      ->capture_default_str();
}

Problem load_problem(const ProblemOptions& o) {
  check_grid_flags(o);
  Problem p{o.line_path.empty() ? data::default_line() : data::load_line(o.line_path),
            o.train_path.empty() ? data::default_train() : data::load_train(o.train_path),
            {}};
  if (o.curve_resistance == "roeckl") p.line.curve_formula = data::CurveFormula::Roeckl;
  if (p.train.pneumatic_brake_N > 0.0 && o.objective == "net") {
    // The DP's regeneration credit does not split braking into regenerative and pneumatic
    // parts yet (the re-simulated ledger does), so the net objective is refused, not misused.
    throw data::InputError("command line", 0, "--objective",
                           "traction for a train with a pneumatic brake (" + o.train_path +
                               "); the net objective does not split the brake yet; got net");
  }
  // TTOBench fields accepted but not modelled are said, never dropped in silence.
  // (Once per run: a load without --from only looks up the line's stops.)
  for (const std::string* path : {&o.line_path, &o.train_path}) {
    if (o.from.empty() || path->empty() || !std::filesystem::is_regular_file(*path)) continue;
    const std::string text = data::read_text_file(*path);
    for (const auto& field : data::ttobench_unmodelled_fields(text)) {
      std::cerr << "ecorail: note: " << *path << ": " << field << "\n";
    }
    for (const auto& w : data::ttobench_metadata_warnings(text)) {
      std::cerr << "ecorail: warning: " << *path << ": " << w << "\n";
    }
  }
  if (!o.from.empty()) {
    const std::vector<std::string> stops = run_stops(p.line, o);
    if (stops.size() > 2) {
      std::string between;
      for (std::size_t i = 1; i + 1 < stops.size(); ++i) between += " --pass-through " + stops[i];
      throw data::InputError("command line", 0, "--to",
                             "a run without intermediate stops for this command (add" + between +
                                 " to run through); got '" + o.to + "', which stops at " +
                                 stops[1]);
    }
    p.route = data::build_route(p.line, o.from, o.to, p.train);
  }
  return p;
}

void add_pass_through_option(CLI::App* cmd, ProblemOptions& o) {
  cmd->add_option("--pass-through", o.pass_through,
                  "intermediate station the run passes without stopping (repeatable; default: "
                  "the run stops at every station between --from and --to)");
}

Problem load_fleet_problem(const ProblemOptions& o, const char* train_flag) {
  ProblemOptions whole = o;
  whole.from.clear();
  Problem p = load_problem(whole);
  if (p.train.has_efficiency_maps()) {
    throw data::InputError("command line", 0, train_flag,
                           "a train with constant efficiencies for the fleet models (they lay "
                           "trips into power bins with one regeneration efficiency); got '" +
                               p.train.name + "', whose efficiencies are maps");
  }
  return p;
}

std::vector<std::string> run_stops(const data::Line& line, const ProblemOptions& o) {
  const std::vector<std::string> all = data::stops_between(line, o.from, o.to);
  for (const auto& name : o.pass_through) {
    if (std::find(all.begin() + 1, all.end() - 1, name) == all.end() - 1) {
      std::string list;
      for (std::size_t i = 1; i + 1 < all.size(); ++i) list += (list.empty() ? "" : ", ") + all[i];
      throw data::InputError("command line", 0, "--pass-through",
                             "a station between --from and --to (" +
                                 (list.empty() ? std::string("none here") : list) + "); got '" +
                                 name + "'");
    }
  }
  std::vector<std::string> stops;
  for (std::size_t i = 0; i < all.size(); ++i) {
    const bool passed =
        i > 0 && i + 1 < all.size() &&
        std::find(o.pass_through.begin(), o.pass_through.end(), all[i]) != o.pass_through.end();
    if (!passed) stops.push_back(all[i]);
  }
  return stops;
}

dp::EngineOptions engine_options(const ProblemOptions& o) {
  check_grid_flags(o);
  dp::EngineOptions e;
  e.grid.ds_m = o.ds_m;
  e.grid.dv_kmh = o.dv_kmh;
  e.grid.substep_m = 0.5 * o.ds_m;
  // --objective is checked against the names by CLI11; the default covers the impossible rest.
  e.objective = dp::objective_from_name(o.objective).value_or(dp::Objective::Traction);
  e.threads = o.threads;  // the library sets OpenMP's thread count per call (dp/threads.hpp)
  e.cruise_as_hold = o.cruise != "grid";
  return e;
}

}  // namespace ecorail::cli
