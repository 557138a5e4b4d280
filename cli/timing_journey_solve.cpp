#include "cli/timing_journey_solve.hpp"

#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "cli/errors.hpp"
#include "cli/progress_line.hpp"
#include "data/csv_reader.hpp"
#include "data/input_error.hpp"
#include "data/route_builder.hpp"
#include "data/ttobench_journey.hpp"
#include "dp/text_format.hpp"
#include "dp/timing_journey.hpp"
#include "output/journey_json.hpp"
#include "output/timeline.hpp"
#include "physics/units.hpp"

namespace ecorail::cli {

namespace {

nlohmann::json bound_or_null(double v) {
  return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
}
nlohmann::json kmh_or_null(double v_ms) {
  return std::isfinite(v_ms) ? nlohmann::json(units::ms_to_kmh(v_ms)) : nlohmann::json(nullptr);
}

std::string binds_text(const std::vector<std::string>& binds) {
  std::string t;
  for (const auto& b : binds) t += (t.empty() ? "" : ",") + b;
  return t.empty() ? "-" : t;
}

nlohmann::json windows_json(const dp::TimingJourneySolution& sol) {
  nlohmann::json list = nlohmann::json::array();
  for (const auto& w : sol.windows) {
    nlohmann::json binds;
    if (w.binds.empty()) {
      binds = nullptr;
    } else if (w.binds.size() == 1) {
      binds = w.binds.front();
    } else {
      binds = w.binds;
    }
    list.push_back({{"position_m", w.window.position_m},
                    {"earliest_s", bound_or_null(w.window.earliest_s)},
                    {"latest_s", bound_or_null(w.window.latest_s)},
                    {"min_speed_kmh", kmh_or_null(w.window.min_speed_ms)},
                    {"max_speed_kmh", kmh_or_null(w.window.max_speed_ms)},
                    {"time_s", bound_or_null(w.time_s)},
                    {"speed_kmh", kmh_or_null(w.speed_ms)},
                    {"met", w.met},
                    {"binds", binds}});
  }
  return list;
}

}  // namespace

void run_timing_journey(const ProblemOptions& problem, const std::string& journey_path,
                        const OutputOptions& outputs, bool full_report, bool quiet) {
  if (problem.line_path.empty() || problem.train_path.empty()) {
    throw data::InputError("command line", 0, "--journey",
                           "--line T.json and --train R.json with it (the journey's track and "
                           "train)");
  }
  check_output_targets(outputs);
  const data::TtobenchJourney journey =
      data::journey_from_ttobench(data::read_text_file(journey_path), journey_path);
  dp::TimingJourneyOptions options;
  options.engine = engine_options(problem);
  std::string why;
  if (!options.IsValid(&why)) throw InvalidOptionsError(why);
  ProblemOptions whole = problem;
  whole.from.clear();
  whole.to.clear();
  const Problem p = load_problem(whole);
  if (p.line.stations.size() < 2) {
    throw data::InputError(problem.line_path, 0, "stops", "at least two stops");
  }
  const physics::Route track =
      data::build_route(p.line, p.line.stations.front().name, p.line.stations.back().name, p.train);
  const std::vector<dp::TimingWindow>& windows = journey.points;
  dp::TimingJourneySolution sol;
  try {
    Progress progress("ecorail solve", quiet);
    progress.update("building the grids", 0, 0);
    sol = dp::solve_timing_journey(p.train, track, windows, options, journey.id);
  } catch (const dp::WindowInfeasibleError& e) {
    throw data::InputError(journey_path, 0,
                           "timing points.values[" + std::to_string(e.point()) + "]",
                           std::string("a window a run can meet: ") + e.what());
  }

  std::FILE* out = report_stream(outputs);
  const dp::TimingJourneySummary& s = sol.summary;
  std::fputs((full_report ? s.FullReport() : s.BriefReport() + warnings_text(s.warnings)).c_str(),
             out);
  std::fprintf(out, "  %-5s %10s %9s %9s %9s %9s %10s %10s  %s\n", "point", "position_m",
               "earliest", "latest", "min_kmh", "max_kmh", "time_s", "speed_kmh", "binds");
  for (std::size_t i = 0; i < sol.windows.size(); ++i) {
    const auto& w = sol.windows[i];
    auto num = [](double v, const char* fmt) {
      return std::isfinite(v) ? dp::format_text(fmt, v) : std::string("-");
    };
    std::fprintf(
        out, "  %-5zu %10.1f %9s %9s %9s %9s %10.2f %10.2f  %s%s\n", i + 1, w.window.position_m,
        num(w.window.earliest_s, "%.1f").c_str(), num(w.window.latest_s, "%.1f").c_str(),
        num(units::ms_to_kmh(w.window.min_speed_ms), "%.1f").c_str(),
        num(units::ms_to_kmh(w.window.max_speed_ms), "%.1f").c_str(), w.time_s,
        units::ms_to_kmh(w.speed_ms), binds_text(w.binds).c_str(), w.met ? "" : "  MISSED");
  }
  std::fflush(out);
  if (!s.IsSolutionUsable()) {
    throw std::runtime_error(
        "the journey misses a timing window or a stop in the re-simulation (see the table); no "
        "output was written");
  }

  std::vector<std::string> stops;
  for (const auto& part : sol.parts) stops.push_back(dp::format_text("%.1f m", part.start_m));
  stops.push_back(dp::format_text("%.1f m", sol.parts.back().end_m));
  const output::Timeline timeline = output::journey_timeline(sol.journey, sol.routes);
  output::JourneyLabels labels{stops, "timing points", problem.ds_m, problem.dv_kmh, 0};
  nlohmann::json report = output::journey_json(sol.journey, labels);
  report["journey"] = journey.id;
  report["windows_met"] = sol.windows_met;
  report["windows"] = windows_json(sol);
  report["trip_time_s"] = s.trip_time_s;
  report["departure_s"] = sol.parts.front().departure_s;
  nlohmann::json parts = nlohmann::json::array();
  for (const auto& part : sol.parts) {
    nlohmann::json lambdas = nlohmann::json::array();
    for (double l : part.stretch_lambda_J_per_s) lambdas.push_back(l / 1000.0);
    parts.push_back({{"from_m", part.start_m},
                     {"to_m", part.end_m},
                     {"departure_s", part.departure_s},
                     {"arrival_target_s", part.arrival_target_s},
                     {"stretch_lambda_kJ_per_s", lambdas},
                     {"price_evaluations", part.evaluations}});
  }
  report["parts"] = parts;
  report["provenance"] = run_provenance(p, problem, {{"journey", journey_path}});
  report["notes"] = nlohmann::json::array();
  char title[256];
  std::snprintf(title, sizeof title, "%s: %.2f s running, traction %.0f kJ", journey.id.c_str(),
                sol.journey.running_time_s, s.traction_energy_kJ);
  output::SummaryRows summary = {{"journey", journey.id},
                                 {"running_time_s", sol.journey.running_time_s},
                                 {"trip_time_s", s.trip_time_s},
                                 {"traction_energy_kJ", s.traction_energy_kJ},
                                 {"regen_energy_kJ", s.regen_energy_kJ},
                                 {"windows_met", sol.windows_met ? "true" : "false"}};
  const physics::Trip trip = dp::journey_trip(
      sol.journey, sol.routes, sol.parts.front().departure_s, p.train.regen_efficiency);
  write_outputs(outputs, report, timeline, title, summary, &trip);
}

}  // namespace ecorail::cli
