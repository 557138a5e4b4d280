#include "cli/journey_solve.hpp"

#include <cmath>
#include <cstdio>
#include <iostream>
#include <map>
#include <stdexcept>

#include "cli/errors.hpp"
#include "data/input_error.hpp"
#include "data/route_builder.hpp"
#include "dp/journey.hpp"
#include "dp/journey_plan.hpp"
#include "output/journey_json.hpp"
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
  require_valid(options);
  ProblemOptions whole = problem;
  whole.from.clear();  // load line and train only; the routes are built per section
  const Problem p = load_problem(whole);
  const std::vector<physics::Route> routes = data::build_routes(p.line, stops, p.train);
  // Errors (a time below the minimum, a proportional share too short) are mapped in one place,
  // cli/errors.cpp.
  const dp::JourneySolution sol = dp::solve_journey(p.train, routes, dwells, time_s, options);

  std::cout << sol.summary.BriefReport();
  std::printf("  %-10s %9s %10s %12s %10s %14s %9s\n", "section", "length_m", "time_s",
              "traction_kJ", "regen_kJ", "marginal_kJ/s", "dwell_s");
  for (std::size_t i = 0; i < sol.sections.size(); ++i) {
    const auto& s = sol.sections[i];
    std::printf("  %-10s %9.1f %10.3f %12.1f %10.1f %14s %9.1f\n",
                (stops[i] + "-" + stops[i + 1]).c_str(), routes[i].length_m(),
                s.run.sim.running_time_s, units::J_to_kJ(s.run.sim.energy.traction_work_J),
                units::J_to_kJ(s.run.sim.energy.regen_J),
                std::isfinite(s.marginal_J_per_s)
                    ? std::to_string(s.marginal_J_per_s / 1000.0).substr(0, 9).c_str()
                    : "-",
                s.dwell_after_s);
  }
  if (full_report) {
    std::fflush(stdout);
    std::cout << sol.summary.FullReport();
  } else {
    for (const auto& w : sol.warnings) std::printf("  warning: %s\n", w.c_str());
  }
  if (!sol.summary.IsSolutionUsable()) {
    std::fflush(stdout);
    throw std::runtime_error(
        "the journey misses a stop or its running time (see the warnings); no output was written");
  }

  const output::Timeline timeline = output::journey_timeline(sol, routes);
  output::JourneyLabels labels{stops, args.split, problem.ds_m, problem.dv_kmh,
                               sol.summary.threads};
  nlohmann::json report = output::journey_json(sol, labels);
  report["provenance"] = run_provenance(
      p, problem, {{"time_s", time_s}, {"dwells", args.dwells}, {"split", args.split}});
  char title[256];
  std::snprintf(title, sizeof title, "%s -> %s (%s split): %.2f s running, traction %.0f kJ",
                stops.front().c_str(), stops.back().c_str(), args.split.c_str(), sol.running_time_s,
                units::J_to_kJ(sol.traction_work_J));
  output::SummaryRows summary = {{"journey", stops.front() + " -> " + stops.back()},
                                 {"split", args.split},
                                 {"running_time_s", sol.running_time_s},
                                 {"traction_energy_kJ", units::J_to_kJ(sol.traction_work_J)},
                                 {"regen_energy_kJ", units::J_to_kJ(sol.regen_J)}};
  write_outputs(outputs, report, timeline, title, summary);
}

}  // namespace ecorail::cli
