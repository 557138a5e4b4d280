#include "cli/problem_options.hpp"

#include <omp.h>

#include "data/input_error.hpp"
#include "data/line_loader.hpp"
#include "data/route_builder.hpp"
#include "data/train_io.hpp"

namespace ecorail::cli {

void add_problem_options(CLI::App* cmd, ProblemOptions& o, bool stations_required) {
  auto* from = cmd->add_option("--from", o.from, "departure station (e.g. A6)");
  auto* to = cmd->add_option("--to", o.to, "arrival station (e.g. A7)");
  if (stations_required) {
    from->required();
    to->required();
  }
  cmd->add_option("--line", o.line_path,
                  "line: a directory of stations/gradients/speed_limits/curves CSVs or a TOML "
                  "file (default: the embedded reference line)");
  cmd->add_option("--train", o.train_path, "train TOML file (default: the reference train)");
  cmd->add_option("--ds", o.ds_m, "grid position step in m")->capture_default_str();
  cmd->add_option("--dv", o.dv_kmh, "grid speed step in km/h")->capture_default_str();
  cmd->add_option("--threads", o.threads, "OpenMP threads (default: all cores)");
  cmd->add_option("--objective", o.objective,
                  "traction: minimise traction energy; net: also credit regenerated energy")
      ->check(CLI::IsMember({"traction", "net"}))
      ->capture_default_str();
}

Problem load_problem(const ProblemOptions& o) {
  if (!(o.ds_m > 0.0 && o.ds_m <= 100.0)) {
    throw data::InputError("command line", 0, "--ds", "a position step in (0, 100] m");
  }
  if (!(o.dv_kmh > 0.0 && o.dv_kmh <= 10.0)) {
    throw data::InputError("command line", 0, "--dv", "a speed step in (0, 10] km/h");
  }
  if (o.threads < 0) throw data::InputError("command line", 0, "--threads", "at least 1");
  if (o.threads > 0) omp_set_num_threads(o.threads);
  Problem p{o.line_path.empty() ? data::default_line() : data::load_line(o.line_path),
            o.train_path.empty() ? data::default_train() : data::load_train(o.train_path),
            {}};
  if (!o.from.empty()) p.route = data::build_route(p.line, o.from, o.to, p.train);
  return p;
}

dp::EngineOptions engine_options(const ProblemOptions& o) {
  dp::EngineOptions e;
  e.grid.ds_m = o.ds_m;
  e.grid.dv_kmh = o.dv_kmh;
  e.grid.substep_m = 0.5 * o.ds_m;
  e.objective = o.objective == "net" ? dp::Objective::Net : dp::Objective::Traction;
  return e;
}

}  // namespace ecorail::cli
