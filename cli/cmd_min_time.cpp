// `ecorail min-time`: the flat-out run of one section (full traction, held on the limits,
// braking for the stop) and its running time, the lower bound for `solve --time`.
#include <cstdio>

#include "cli/commands.hpp"
#include "cli/output_options.hpp"
#include "cli/problem_options.hpp"
#include "output/run_json.hpp"
#include "output/solve_reports.hpp"
#include "physics/trip.hpp"
#include "physics/units.hpp"

namespace ecorail::cli {

namespace {

struct MinTimeArgs {
  ProblemOptions problem;
  OutputOptions outputs;
};

void run_min_time(const MinTimeArgs& a) {
  check_output_targets(a.outputs);
  const Problem p = load_problem(a.problem);
  const physics::SpeedEnvelope envelope(p.train, p.route);
  const physics::Motion motion(p.train, p.route, envelope);
  const physics::SimulationResult sim =
      physics::simulate(motion, {{0.0, physics::Control::MaxTraction}}, {});
  std::printf(
      "ecorail min-time %s -> %s (%.1f m): minimum running time %.3f s, traction %.1f kJ, "
      "stop error %.3f m\n",
      p.route.from_name().c_str(), p.route.to_name().c_str(), p.route.length_m(),
      sim.running_time_s, units::J_to_kJ(sim.energy.traction_work_J), sim.stop_error_m);
  const nlohmann::json j =
      output::min_time_report_json(p.route, sim, p.train, run_provenance(p, a.problem));
  // The per-second table is read from the run laid out as a trip.
  const output::Timeline timeline =
      output::trip_timeline(physics::Trip({{&p.route, &sim, 0.0}}, 0.0, p.train.regen_efficiency));
  char title[200];
  std::snprintf(title, sizeof title, "%s -> %s flat out: %.2f s", p.route.from_name().c_str(),
                p.route.to_name().c_str(), sim.running_time_s);
  write_outputs(a.outputs, j, timeline, title, {});
}

}  // namespace

void add_min_time_command(CLI::App& app) {
  auto args = std::make_shared<MinTimeArgs>();
  CLI::App* cmd = app.add_subcommand("min-time", "minimum running time of a section");
  add_problem_options(cmd, args->problem);
  add_output_options(cmd, args->outputs);
  cmd->callback([args] { run_min_time(*args); });
}

}  // namespace ecorail::cli
