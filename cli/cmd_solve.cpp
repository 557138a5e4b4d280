// `ecorail solve`: the energy-optimal run of one section for a running time.
#include <cstdio>
#include <iostream>
#include <stdexcept>

#include "cli/commands.hpp"
#include "cli/errors.hpp"
#include "cli/journey_solve.hpp"
#include "cli/output_options.hpp"
#include "cli/problem_options.hpp"
#include "data/input_error.hpp"
#include "data/route_builder.hpp"
#include "dp/journey.hpp"
#include "dp/section_solve.hpp"
#include "output/run_json.hpp"
#include "physics/trip.hpp"
#include "physics/units.hpp"

namespace ecorail::cli {

namespace {

struct SolveArgs {
  ProblemOptions problem;
  OutputOptions outputs;
  JourneyArgs journey;
  double time_s = 0.0;
  bool full_report = false;
};

void print_regimes(const std::vector<dp::RegimeSpan>& spans) {
  std::printf("  %-17s %9s %9s %9s %9s %8s %8s\n", "regime", "from_m", "to_m", "v0_kmh", "v1_kmh",
              "t0_s", "t1_s");
  for (const auto& r : spans) {
    std::printf("  %-17s %9.2f %9.2f %9.2f %9.2f %8.2f %8.2f\n",
                std::string(physics::regime_name(r.regime)).c_str(), r.start_m, r.end_m,
                units::ms_to_kmh(r.start_speed_ms), units::ms_to_kmh(r.end_speed_ms),
                r.start_time_s, r.end_time_s);
  }
}

output::SummaryRows summary_rows(const dp::SectionSolveSummary& s) {
  return {{"section", s.from + " -> " + s.to},
          {"distance_m", s.distance_m},
          {"target_time_s", s.target_time_s},
          {"running_time_s", s.running_time_s},
          {"traction_energy_kJ", s.traction_energy_kJ},
          {"regen_energy_kJ", s.regen_energy_kJ},
          {"net_energy_kJ", s.net_energy_kJ},
          {"stop_error_m", s.stop_error_m},
          {"max_overspeed_kmh", s.max_overspeed_kmh},
          {"lambda_kJ_per_s", s.lambda_J_per_s / 1000.0},
          {"grid_ds_m", s.grid.ds_m},
          {"grid_dv_kmh", s.grid.dv_kmh}};
}

void run_solve(const SolveArgs& a) {
  if (!(a.time_s > 0.0)) {
    throw data::InputError("command line", 0, "--time", "a running time in seconds > 0");
  }
  check_output_targets(a.outputs);
  {
    ProblemOptions line_only = a.problem;
    line_only.from.clear();
    const std::vector<std::string> stops = run_stops(load_problem(line_only).line, a.problem);
    if (stops.size() > 2) {
      run_journey(a.problem, a.journey, a.outputs, a.time_s, a.full_report, stops);
      return;
    }
  }
  dp::SectionSolveOptions options;
  options.engine = engine_options(a.problem);
  require_valid(options);
  const Problem p = load_problem(a.problem);
  const dp::SectionSolution solution = dp::solve_section(p.train, p.route, a.time_s, options);
  const auto& s = solution.summary;
  std::cout << (a.full_report ? s.FullReport() : s.BriefReport());
  if (!s.IsSolutionUsable()) {
    for (const auto& w : s.warnings) std::cout << "  warning: " << w << "\n";
    throw std::runtime_error(
        "the run misses its stop or its running time (see the warnings); "
        "no output was written");
  }
  print_regimes(solution.regimes);
  // The per-second table is read from the run laid out as a trip.
  const output::Timeline timeline = output::trip_timeline(
      physics::Trip({{&p.route, &solution.run.sim, 0.0}}, 0.0, p.train.regen_efficiency));
  char title[256];
  std::snprintf(title, sizeof title, "%s -> %s: %.2f s, traction %.0f kJ", s.from.c_str(),
                s.to.c_str(), s.running_time_s, s.traction_energy_kJ);
  nlohmann::json report = output::section_solution_json(solution);
  report["provenance"] = run_provenance(p, a.problem, {{"time_s", a.time_s}});
  write_outputs(a.outputs, report, timeline, title, summary_rows(s));
}

}  // namespace

void add_solve_command(CLI::App& app) {
  auto args = std::make_shared<SolveArgs>();
  CLI::App* cmd = app.add_subcommand("solve", "energy-optimal run for a running time");
  add_problem_options(cmd, args->problem);
  cmd->add_option("--time", args->time_s, "running time in s (dwells excluded)")->required();
  cmd->add_flag("--full-report", args->full_report, "print the full solver report");
  cmd->add_option("--dwell", args->journey.dwells,
                  "dwell at intermediate stops: STATION=SECONDS, or SECONDS for every stop "
                  "not named (journeys only)");
  cmd->add_option("--split", args->journey.split,
                  "optimal: one lambda for all sections; proportional: time in proportion to "
                  "distance")
      ->check(CLI::IsMember({std::string(dp::split_name(dp::Split::Optimal)),
                             std::string(dp::split_name(dp::Split::Proportional))}))
      ->capture_default_str();
  cmd->add_option("--marginals", args->journey.marginals,
                  "measure each section's marginal energy per second (+-0.5 s re-solves): "
                  "on, off, auto (on up to 4 sections)")
      ->check(CLI::IsMember({"on", "off", "auto"}))
      ->capture_default_str();
  add_output_options(cmd, args->outputs);
  cmd->callback([args] { run_solve(*args); });
}

}  // namespace ecorail::cli
