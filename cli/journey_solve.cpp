#include "cli/journey_solve.hpp"

#include <omp.h>

#include <cmath>
#include <cstdio>
#include <iostream>
#include <map>
#include <stdexcept>

#include "data/csv_reader.hpp"
#include "data/input_error.hpp"
#include "data/route_builder.hpp"
#include "dp/journey.hpp"
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
  std::map<std::string, double> named;
  double fallback = NAN;
  for (const auto& value : values) {
    const auto eq = value.find('=');
    if (eq == std::string::npos) {
      fallback = parse_seconds(value, value);
      continue;
    }
    const std::string station = value.substr(0, eq);
    bool intermediate = false;
    for (std::size_t i = 1; i + 1 < stops.size(); ++i) intermediate |= stops[i] == station;
    if (!intermediate) {
      std::string list;
      for (std::size_t i = 1; i + 1 < stops.size(); ++i)
        list += (list.empty() ? "" : ", ") + stops[i];
      throw data::InputError(
          "command line", 0, "--dwell",
          "an intermediate stop of this run (" + list + "); got '" + station + "'");
    }
    named[station] = parse_seconds(value.substr(eq + 1), value);
  }
  std::vector<double> dwells;
  for (std::size_t i = 1; i + 1 < stops.size(); ++i) {
    auto it = named.find(stops[i]);
    if (it != named.end()) {
      dwells.push_back(it->second);
    } else if (std::isfinite(fallback)) {
      dwells.push_back(fallback);
    } else {
      throw data::InputError("command line", 0, "--dwell",
                             "a dwell for the intermediate stop " + stops[i] + " (--dwell " +
                                 stops[i] + "=45, or --dwell 30 for every stop)");
    }
  }
  return dwells;
}

void run_journey(const ProblemOptions& problem, const JourneyArgs& args,
                 const OutputOptions& outputs, double time_s, bool full_report,
                 const std::vector<std::string>& stops) {
  const std::vector<double> dwells = parse_dwells(args.dwells, stops);
  ProblemOptions whole = problem;
  whole.from.clear();  // load line and train only; the routes are built per section
  const Problem p = load_problem(whole);
  std::vector<physics::Route> routes;
  for (std::size_t i = 0; i + 1 < stops.size(); ++i) {
    routes.push_back(data::build_route(p.line, stops[i], stops[i + 1], p.train));
  }
  dp::JourneyOptions options;
  options.engine = engine_options(problem);
  options.split = args.split == "proportional" ? dp::Split::Proportional : dp::Split::Optimal;
  options.measure_marginals =
      args.marginals == "on" || (args.marginals == "auto" && routes.size() <= 4);
  dp::JourneySolution sol;
  try {
    sol = dp::solve_journey(p.train, routes, dwells, time_s, options);
  } catch (const dp::InfeasibleTimeError& e) {
    char expected[240];
    std::snprintf(expected, sizeof expected,
                  "at least the minimum running time of %.2f s for %s -> %s (sum of flat-out "
                  "sections, dwells excluded); got %.2f s",
                  e.minimum_s(), stops.front().c_str(), stops.back().c_str(), time_s);
    throw data::InputError("command line", 0, "--time", expected);
  } catch (const std::invalid_argument& e) {
    throw data::InputError("command line", 0, "--time", e.what());
  }

  std::printf(
      "ecorail solve %s -> %s (%zu sections, %s split) in %.3f s running time: traction %.1f "
      "kJ, regenerated %.1f kJ%s, %.3f s wall, %s\n",
      stops.front().c_str(), stops.back().c_str(), routes.size(), args.split.c_str(),
      sol.running_time_s, units::J_to_kJ(sol.traction_work_J), units::J_to_kJ(sol.regen_J),
      std::isfinite(sol.lambda_J_per_s)
          ? (", lambda " + std::to_string(sol.lambda_J_per_s / 1000.0) + " kJ/s").c_str()
          : "",
      sol.total_wall_s, sol.converged && sol.warnings.empty() ? "CONVERGENCE" : "WARNINGS");
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
    std::printf("  lambda evaluations %d, build %.3f s, search %.3f s, total %.3f s\n",
                sol.lambda_evaluations, sol.build_wall_s, sol.search_wall_s, sol.total_wall_s);
  }
  for (const auto& w : sol.warnings) std::printf("  warning: %s\n", w.c_str());
  if (!sol.converged) {
    std::fflush(stdout);
    throw std::runtime_error(
        "the journey misses a stop or its running time (see the warnings); no output was written");
  }

  output::Timeline timeline;
  for (std::size_t i = 0; i < sol.sections.size(); ++i) {
    output::append_section(timeline, sol.sections[i].run.sim, routes[i], static_cast<int>(i));
    if (i + 1 < sol.sections.size()) output::append_dwell(timeline, sol.sections[i].dwell_after_s);
  }
  output::JourneyLabels labels{stops, args.split, problem.ds_m, problem.dv_kmh,
                               omp_get_max_threads()};
  const nlohmann::json report = output::journey_json(sol, labels);
  char title[256];
  std::snprintf(title, sizeof title, "%s -> %s (%s split): %.2f s running, traction %.0f kJ",
                stops.front().c_str(), stops.back().c_str(), args.split.c_str(), sol.running_time_s,
                units::J_to_kJ(sol.traction_work_J));
  output::SummaryRows summary = {
      {"journey", stops.front() + " -> " + stops.back()},
      {"split", args.split},
      {"running_time_s", std::to_string(sol.running_time_s)},
      {"traction_energy_kJ", std::to_string(units::J_to_kJ(sol.traction_work_J))},
      {"regen_energy_kJ", std::to_string(units::J_to_kJ(sol.regen_J))}};
  write_outputs(outputs, report, timeline, title, summary);
}

}  // namespace ecorail::cli
