#include "cli/journey_solve.hpp"

#include <cmath>
#include <cstdio>
#include <iostream>
#include <map>
#include <optional>
#include <stdexcept>

#include "cli/errors.hpp"
#include "cli/progress_line.hpp"
#include "data/atomic_file.hpp"
#include "data/input_error.hpp"
#include "data/route_builder.hpp"
#include "dp/journey.hpp"
#include "dp/journey_plan.hpp"
#include "dp/text_format.hpp"
#include "output/journey_json.hpp"
#include "output/run_json.hpp"
#include "output/solve_reports.hpp"
#include "physics/units.hpp"

namespace ecorail::cli {

namespace {

double parse_seconds(const std::string& text, const std::string& value) {
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0' || !std::isfinite(v) || v < 0.0) {
    throw data::InputError(
        "command line", 0, "--dwell",
        "a dwell in seconds >= 0 (e.g. --dwell 30 or --dwell A7=45); got '" + value + "'");
  }
  return v;
}

}  // namespace

std::FILE* report_stream(const OutputOptions& o) {
  for (const std::string* path : {&o.json, &o.csv, &o.xlsx, &o.plot}) {
    if (!path->empty() && data::is_stdout_path(*path)) return stderr;
  }
  return stdout;
}

std::string warnings_text(const std::vector<std::string>& warnings) {
  std::string text;
  for (const auto& w : warnings) text += "  warning: " + w + "\n";
  return text;
}

std::vector<double> parse_dwells(const std::vector<std::string>& values,
                                 const std::vector<std::string>& stops) {
  dp::DwellSpec spec;
  for (const auto& value : values) {
    const auto eq = value.find('=');
    if (eq == std::string::npos) {
      spec.every_stop_s = parse_seconds(value, value);
    } else {
      spec.by_stop_s.emplace_back(value.substr(0, eq), parse_seconds(value.substr(eq + 1), value));
    }
  }
  return dp::resolve_dwells(spec, stops);  // DwellError: an error on --dwell (cli/errors.cpp)
}

void run_journey(const ProblemOptions& problem, const JourneyArgs& args,
                 const OutputOptions& outputs, double time_s, bool full_report,
                 const std::vector<std::string>& stops) {
  const std::vector<double> dwells = parse_dwells(args.dwells, stops);
  dp::JourneyOptions options;
  options.engine = engine_options(problem);
  options.split = dp::split_from_name(args.split).value_or(dp::Split::Optimal);
  options.measure_marginals =
      args.marginals == "on" || (args.marginals == "auto" && stops.size() - 1 <= 4);
  options.min_regime = args.min_regime;
  require_valid(options);
  ProblemOptions whole = problem;
  whole.from.clear();  // load line and train only; the routes are built per section
  const Problem p = load_problem(whole);
  const std::vector<physics::Route> routes = data::build_routes(p.line, stops, p.train);
  // Errors (a time below the minimum, a proportional share too short) are mapped in one place,
  // cli/errors.cpp.
  dp::JourneySolution sol;
  {
    Progress progress("ecorail solve", args.quiet);
    progress.update("building the grids", 0, 0);
    options.search.progress = progress.callback();
    sol = dp::solve_journey(p.train, routes, dwells, time_s, options);
  }

  std::FILE* out = report_stream(outputs);
  std::fputs(sol.summary.BriefReport().c_str(), out);
  const std::string cap_note = output::speed_cap_note(p.line, stops, p.train);
  if (!cap_note.empty()) std::fprintf(out, "  note: %s\n", cap_note.c_str());
  if (sol.summary.streamed_tables) {
    std::fprintf(out,
                 "  note: the sections' transition tables (%.2f GiB together) exceed half of the "
                 "memory this process can have, so each is built per sweep and freed (same "
                 "result, slower)\n",
                 sol.summary.tables_estimate_bytes / 1073741824.0);
  }
  if (options.min_regime.active()) {
    const double cost_kJ = units::J_to_kJ(sol.merged_cost_J - sol.unmerged_cost_J);
    std::fprintf(
        out,
        "  minimum regime %.0f m / %.0f s: %d phases merged, energy %+.1f kJ (%+.4f %%) "
        "against the unmerged optimum of %.1f kJ\n",
        options.min_regime.min_length_m, options.min_regime.min_duration_s, sol.merged_regimes,
        cost_kJ,
        sol.unmerged_cost_J > 0.0 ? 100.0 * (sol.merged_cost_J / sol.unmerged_cost_J - 1.0) : 0.0,
        units::J_to_kJ(sol.unmerged_cost_J));
  }
  // Per section: what it took, what it used, and whether it met its stop and its limits.
  std::fprintf(out, "  %-10s %9s %10s %12s %10s %14s %9s %11s %13s\n", "section", "length_m",
               "time_s", "traction_kJ", "regen_kJ", "marginal_kJ/s", "dwell_s", "stop_err_m",
               "overspeed_kmh");
  for (std::size_t i = 0; i < sol.sections.size(); ++i) {
    const auto& s = sol.sections[i];
    const std::string marginal = std::isfinite(s.marginal_J_per_s)
                                     ? dp::format_text("%.3f", s.marginal_J_per_s / 1000.0)
                                     : "-";
    std::fprintf(out, "  %-10s %9.1f %10.3f %12.1f %10.1f %14s %9.1f %11.3f %13.3f\n",
                 (stops[i] + "-" + stops[i + 1]).c_str(), routes[i].length_m(),
                 s.run.sim.running_time_s, units::J_to_kJ(s.run.sim.energy.traction_work_J),
                 units::J_to_kJ(s.run.sim.energy.regen_J), marginal.c_str(), s.dwell_after_s,
                 s.run.sim.stop_error_m,
                 units::ms_to_kmh(std::max(0.0, s.run.sim.max_overspeed_ms)));
  }
  std::fputs(full_report ? sol.summary.FullReport().c_str() : warnings_text(sol.warnings).c_str(),
             out);
  std::fflush(out);
  if (!sol.summary.IsSolutionUsable()) {
    throw std::runtime_error(
        "the journey misses a stop or its running time (see the warnings); no output was written");
  }

  const output::Timeline timeline =
      outputs.needs_timeline() ? output::journey_timeline(sol, routes) : output::Timeline{};
  output::JourneyLabels labels{stops, args.split, problem.ds_m, problem.dv_kmh,
                               sol.summary.threads};
  const nlohmann::json report = output::journey_report_json(
      sol, labels, p.train, cap_note, args.min_regime,
      run_provenance(p, problem,
                     {{"time_s", time_s},
                      {"dwells", args.dwells},
                      {"split", args.split},
                      {"min_regime_m", args.min_regime.min_length_m},
                      {"min_regime_s", args.min_regime.min_duration_s}}));
  char title[256];
  std::snprintf(title, sizeof title, "%s -> %s (%s split): %.2f s running, traction %.0f kJ",
                stops.front().c_str(), stops.back().c_str(), args.split.c_str(), sol.running_time_s,
                units::J_to_kJ(sol.traction_work_J));
  output::SummaryRows summary = {{"journey", stops.front() + " -> " + stops.back()},
                                 {"split", args.split},
                                 {"running_time_s", sol.running_time_s},
                                 {"traction_energy_kJ", units::J_to_kJ(sol.traction_work_J)},
                                 {"regen_energy_kJ", units::J_to_kJ(sol.regen_J)}};
  std::optional<physics::Trip> trip;
  if (outputs.needs_trip()) trip = dp::journey_trip(sol, routes, 0.0, p.train.regen_efficiency);
  write_outputs(outputs, report, timeline, title, summary, trip ? &*trip : nullptr, &p.line);
}

}  // namespace ecorail::cli
