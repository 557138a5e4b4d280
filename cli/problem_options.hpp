// Options every engine command shares (--line, --train, --from, --to, --pass-through, --ds,
// --dv, --threads, --objective) and the loading of the problem they describe.
//
// --from/--to mean one thing in every command: a run that stops at every station between them.
// --pass-through STATION (repeatable) names an intermediate station the run passes without
// stopping; the run then stops only at the remaining stations (run_stops), and each leg between
// two consecutive stops is one route built non-stop over the stations it passes.
#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "data/line.hpp"
#include "dp/section_engine.hpp"
#include "physics/route.hpp"
#include "physics/train.hpp"

namespace ecorail::cli {

struct ProblemOptions {
  std::string line_path;   // empty: the embedded reference line
  std::string train_path;  // empty: the embedded reference train
  std::string from, to;
  std::vector<std::string> pass_through;  // intermediate stations passed without stopping
  double ds_m = 5.0;
  double dv_kmh = 0.2;
  int threads = 0;                         // 0: OpenMP's default
  std::string objective = "traction";      // a dp::objective_name
  std::string curve_resistance = "600/R";  // or "roeckl" (data::CurveFormula)
  std::string cruise = "hold";  // "hold": cruising as one polished hold; "grid": the grid's own
};

struct Problem {
  data::Line line;
  physics::Train train;
  physics::Route route;
};

void add_problem_options(CLI::App* cmd, ProblemOptions& o, bool stations_required = true);
// Loads line and train and builds the route; InputError on bad input. (Threads are not set
// here: engine_options carries --threads into the library's options.)
// With from/to set, the route is the single leg from -> to and must not stop on the way: a run
// over several stops is refused here (use run_stops and one route per leg).
Problem load_problem(const ProblemOptions& o);
// The whole line and the train for the many-train commands (timetable, delay, montecarlo):
// load_problem without a route. Their fleet models lay trips into power bins with the train's
// constant regeneration efficiency, so a train with efficiency maps is refused here (InputError
// on train_flag, the flag that named the train file) rather than reported with the wrong
// efficiency.
Problem load_fleet_problem(const ProblemOptions& o, const char* train_flag = "--train");
// The stops of the run from --from to --to: every station between them except the
// --pass-through ones, both ends included, in the order of travel. InputError for a
// --pass-through station that is not strictly between --from and --to.
std::vector<std::string> run_stops(const data::Line& line, const ProblemOptions& o);
// Registers --pass-through on a command (add_problem_options does it for every command that
// uses the shared options).
void add_pass_through_option(CLI::App* cmd, ProblemOptions& o);
// The engine options of --ds, --dv, --objective and --threads (checked by the caller with
// require_valid before any work).
dp::EngineOptions engine_options(const ProblemOptions& o);

}  // namespace ecorail::cli
