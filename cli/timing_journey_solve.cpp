#include "cli/timing_journey_solve.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <stdexcept>

#include "cli/errors.hpp"
#include "cli/progress_line.hpp"
#include "data/csv_reader.hpp"
#include "data/input_error.hpp"
#include "data/route_builder.hpp"
#include "data/ttobench_io.hpp"
#include "data/ttobench_journey.hpp"
#include "dp/text_format.hpp"
#include "dp/timing_journey.hpp"
#include "output/journey_json.hpp"
#include "output/solve_reports.hpp"
#include "output/timeline.hpp"
#include "physics/units.hpp"

namespace ecorail::cli {

namespace {

std::string binds_text(const std::vector<std::string>& binds) {
  std::string t;
  for (const auto& b : binds) t += (t.empty() ? "" : ",") + b;
  return t.empty() ? "-" : t;
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
  // Metadata keys TTOBench does not define are kept and said (the track's and train's too: the
  // whole-track load below names no stops, so load_problem does not say them).
  for (const std::string* path : {&problem.line_path, &problem.train_path, &journey_path}) {
    if (!std::filesystem::is_regular_file(*path)) continue;
    for (const auto& w : data::ttobench_metadata_warnings(data::read_text_file(*path))) {
      std::fprintf(stderr, "ecorail: warning: %s: %s\n", path->c_str(), w.c_str());
    }
  }
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
    options.progress = progress.callback();
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

  const output::Timeline timeline = outputs.needs_timeline()
                                        ? output::journey_timeline(sol.journey, sol.routes)
                                        : output::Timeline{};
  const nlohmann::json report =
      output::timing_journey_report_json(sol, journey.id, problem.ds_m, problem.dv_kmh,
                                         run_provenance(p, problem, {{"journey", journey_path}}));
  char title[256];
  std::snprintf(title, sizeof title, "%s: %.2f s running, traction %.0f kJ", journey.id.c_str(),
                sol.journey.running_time_s, s.traction_energy_kJ);
  output::SummaryRows summary = {{"journey", journey.id},
                                 {"running_time_s", sol.journey.running_time_s},
                                 {"trip_time_s", s.trip_time_s},
                                 {"traction_energy_kJ", s.traction_energy_kJ},
                                 {"regen_energy_kJ", s.regen_energy_kJ},
                                 {"windows_met", sol.windows_met ? "true" : "false"}};
  std::optional<physics::Trip> trip;
  if (outputs.needs_trip()) {
    trip = dp::journey_trip(sol.journey, sol.routes, sol.parts.front().departure_s,
                            p.train.regen_efficiency);
  }
  write_outputs(outputs, report, timeline, title, summary, trip ? &*trip : nullptr, &p.line);
}

}  // namespace ecorail::cli
