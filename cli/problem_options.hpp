// Options every engine command shares (--line, --train, --from, --to, --ds, --dv, --threads,
// --objective) and the loading of the problem they describe.
#pragma once

#include <CLI/CLI.hpp>
#include <string>

#include "data/line.hpp"
#include "dp/section_engine.hpp"
#include "physics/route.hpp"
#include "physics/train.hpp"

namespace ecorail::cli {

struct ProblemOptions {
  std::string line_path;   // empty: the embedded reference line
  std::string train_path;  // empty: the embedded reference train
  std::string from, to;
  double ds_m = 5.0;
  double dv_kmh = 0.2;
  int threads = 0;  // 0: OpenMP's default
  std::string objective = "traction";
};

struct Problem {
  data::Line line;
  physics::Train train;
  physics::Route route;
};

void add_problem_options(CLI::App* cmd, ProblemOptions& o, bool stations_required = true);
// Loads line and train, builds the route, applies --threads; InputError on bad input.
Problem load_problem(const ProblemOptions& o);
dp::EngineOptions engine_options(const ProblemOptions& o);

}  // namespace ecorail::cli
