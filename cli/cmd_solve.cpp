// `ecorail solve`: the energy-optimal run of one section for a running time.
#include <cstdio>
#include <iostream>
#include <stdexcept>

#include "cli/commands.hpp"
#include "cli/errors.hpp"
#include "cli/journey_solve.hpp"
#include "cli/output_options.hpp"
#include "cli/problem_options.hpp"
#include "cli/progress_line.hpp"
#include "cli/timing_journey_solve.hpp"
#include "data/input_error.hpp"
#include "data/route_builder.hpp"
#include "dp/journey.hpp"
#include "dp/section_solve.hpp"
#include "dp/text_format.hpp"
#include "output/run_json.hpp"
#include "output/solve_reports.hpp"
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
  std::string journey_path;  // --journey: a TTOBench journey with timing points
};

// A speed hold is named as one ("speed_hold"), so the table reads as advice.
void print_regimes(std::FILE* out, const std::vector<dp::RegimeSpan>& spans) {
  std::fprintf(out, "  %-17s %9s %9s %9s %9s %8s %8s\n", "regime", "from_m", "to_m", "v0_kmh",
               "v1_kmh", "t0_s", "t1_s");
  for (const auto& r : spans) {
    std::fprintf(out, "  %-17s %9.2f %9.2f %9.2f %9.2f %8.2f %8.2f\n",
                 std::string(dp::span_name(r)).c_str(), r.start_m, r.end_m,
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
          {"min_regime_m", s.min_regime.min_length_m},
          {"min_regime_s", s.min_regime.min_duration_s},
          {"min_regime_cost_kJ", s.min_regime_cost_kJ},
          {"grid_ds_m", s.grid.ds_m},
          {"grid_dv_kmh", s.grid.dv_kmh}};
}

void run_solve(const SolveArgs& a, const CLI::App& cmd) {
  if (!a.journey_path.empty()) {
    // The journey file gives the stops and the times.
    for (const char* flag : {"--from", "--to", "--time", "--pass-through", "--dwell", "--split",
                             "--min-regime-m", "--min-regime-s", "--marginals"}) {
      if (cmd.count(flag) > 0) {
        throw data::InputError("command line", 0, flag,
                               "no " + std::string(flag) +
                                   " with --journey (the journey file gives the stops and the "
                                   "times)");
      }
    }
    run_timing_journey(a.problem, a.journey_path, a.outputs, a.full_report, a.journey.quiet);
    return;
  }
  for (const char* flag : {"--from", "--to", "--time"}) {
    if (cmd.count(flag) == 0) throw CLI::RequiredError(flag);
  }
  if (!(a.time_s > 0.0)) {
    throw data::InputError("command line", 0, "--time", "a running time in seconds > 0");
  }
  check_output_targets(a.outputs);
  {
    ProblemOptions line_only = a.problem;
    line_only.from.clear();
    const data::Line line = load_problem(line_only).line;
    const std::vector<std::string> stops = run_stops(line, a.problem);
    check_gtfs_stops(a.outputs, line, stops);
    if (stops.size() > 2) {
      run_journey(a.problem, a.journey, a.outputs, a.time_s, a.full_report, stops);
      return;
    }
  }
  dp::SectionSolveOptions options;
  options.engine = engine_options(a.problem);
  options.min_regime = a.journey.min_regime;
  require_valid(options);
  const Problem p = load_problem(a.problem);
  std::FILE* out = report_stream(a.outputs);
  dp::SectionSolution solution;
  {
    Progress progress("ecorail solve", a.journey.quiet);
    progress.update("building the grid", 0, 0);
    options.search.progress = progress.callback();
    solution = dp::solve_section(p.train, p.route, a.time_s, options);
  }
  const auto& s = solution.summary;
  // Warnings go with either report (the full one lists them itself).
  std::fputs((a.full_report ? s.FullReport() : s.BriefReport() + warnings_text(s.warnings)).c_str(),
             out);
  const std::string cap_note = output::speed_cap_note(p.line, {s.from, s.to}, p.train);
  if (!cap_note.empty()) std::fprintf(out, "  note: %s\n", cap_note.c_str());
  if (!s.IsSolutionUsable()) {
    std::fflush(out);
    throw std::runtime_error(
        "the run misses its stop or its running time (see the warnings); "
        "no output was written");
  }
  print_regimes(out, solution.regimes);
  std::fflush(out);
  // The per-second table is read from the run laid out as a trip.
  const physics::Trip trip({{&p.route, &solution.run.sim, 0.0}}, 0.0, p.train.regen_efficiency);
  const output::Timeline timeline = output::trip_timeline(trip);
  char title[256];
  std::snprintf(title, sizeof title, "%s -> %s: %.2f s, traction %.0f kJ", s.from.c_str(),
                s.to.c_str(), s.running_time_s, s.traction_energy_kJ);
  const nlohmann::json report = output::section_report_json(
      solution, p.train, cap_note,
      run_provenance(p, a.problem,
                     {{"time_s", a.time_s},
                      {"min_regime_m", options.min_regime.min_length_m},
                      {"min_regime_s", options.min_regime.min_duration_s}}));
  write_outputs(a.outputs, report, timeline, title, summary_rows(s), &trip, &p.line);
}

}  // namespace

void add_solve_command(CLI::App& app) {
  auto args = std::make_shared<SolveArgs>();
  CLI::App* cmd = app.add_subcommand("solve", "energy-optimal run for a running time");
  // --from, --to and --time are required unless --journey gives the stops and times.
  add_problem_options(cmd, args->problem, false);
  cmd->add_option("--time", args->time_s, "running time in s (dwells excluded)");
  cmd->add_option("--journey", args->journey_path,
                  "a TTOBench journey (timing points with time and speed windows) on the --line "
                  "track; instead of --from/--to/--time (docs/ttobench.md)");
  cmd->add_flag("--full-report", args->full_report, "print the full solver report");
  cmd->add_option("--min-regime-m", args->journey.min_regime.min_length_m,
                  "merge control phases shorter than this (m) into the phase before them, "
                  "re-simulate and trim back to the running time; the report states the cost "
                  "(docs/journeys.md)");
  cmd->add_option("--min-regime-s", args->journey.min_regime.min_duration_s,
                  "the same for phases lasting less than this (s)");
  cmd->add_flag("--quiet", args->journey.quiet, "no progress line on stderr");
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
  add_gtfs_options(cmd, args->outputs);
  input_files(cmd, {"--journey"});
  cmd->callback([args, cmd] { run_solve(*args, *cmd); });
}

}  // namespace ecorail::cli
