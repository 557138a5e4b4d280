// `ecorail delay`: one train leaves a station late (question 3.1). Reads the plan (the 2.1
// reference plan or a timetable CSV as `ecorail timetable ... --csv` writes it), hands it to
// recovery::recover_delay and prints and writes what it found: where the train is back on
// time, the new running times and dwells, traction energy against the plan and the seed
// paper's rule, and the followers' separation margins (docs/delays.md).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "cli/commands.hpp"
#include "cli/errors.hpp"
#include "cli/journey_solve.hpp"
#include "cli/output_options.hpp"
#include "cli/plan_input.hpp"
#include "cli/problem_options.hpp"
#include "data/atomic_file.hpp"
#include "data/csv_reader.hpp"
#include "data/input_error.hpp"
#include "data/route_builder.hpp"
#include "data/train_io.hpp"
#include "dp/section_library.hpp"
#include "output/frontier_cache.hpp"
#include "output/gnuplot.hpp"
#include "output/speed_plot.hpp"
#include "output/timeline.hpp"
#include "recovery/delay_recovery.hpp"
#include "recovery/delay_report.hpp"

namespace ecorail::cli {

namespace {

struct DelayArgs {
  ProblemOptions problem;  // --line, --train-file, --ds, --dv, --threads, --objective
  std::string plan_file;
  bool reference = false;
  int train = 0;  // 1-based
  std::string station;
  double delay_s = std::nan("");
  double min_dwell_s = 30.0;
  int followers = 5;
  bool lateness_first = false;
  bool followers_wait = false;
  double frontier_span_s = 60.0;
  std::string cache_dir;
  bool no_cache = false;
  bool full_report = false;
  bool quiet = false;
  std::string json, csv, svg;
};

void print_report(std::FILE* out, const recovery::DelayRecoveryResult& r, bool full) {
  const auto& sm = r.summary;
  std::fputs((full ? sm.FullReport() : sm.BriefReport() + warnings_text(sm.warnings)).c_str(), out);
  std::fprintf(out, "  %-9s %9s %9s %9s %9s %11s %11s %11s %9s %9s\n", "section", "min_s", "plan_s",
               "new_s", "rule_s", "plan_kJ", "new_kJ", "rule_kJ", "marg_kJ/s", "dwell_s");
  for (const auto& s : r.sections) {
    const std::string name = s.from + "-" + s.to;
    std::fprintf(out, "  %-9s %9.3f %9.3f %9.3f %9.3f %11.1f %11.1f %11.1f %9s %9.3f\n",
                 name.c_str(), s.min_time_s, s.planned_time_s, s.new_time_s, s.rule_time_s,
                 s.plan_energy_kJ, s.new_energy_kJ, s.rule_energy_kJ,
                 std::isfinite(s.marginal_kJ_per_s)
                     ? data::format_number(std::round(s.marginal_kJ_per_s * 1000) / 1000).c_str()
                     : "flat-out",
                 s.new_dwell_s);
  }
  for (const auto& t : r.trains) {
    std::string what = t.never_late ? "held up, but never late"
                       : t.back_on_time_at.empty()
                           ? "not back on time, " + data::format_number(t.final_lateness_s) +
                                 " s late at the last station"
                           : "back on time at " + t.back_on_time_at;
    std::fprintf(out, "  train %d: %s (largest lateness %.2f s)\n", t.train + 1, what.c_str(),
                 t.max_lateness_s);
  }
  auto kmh = [](double v) {
    return std::isfinite(v) ? data::format_number(std::round(v * 100) / 100) + " km/h"
                            : std::string("none (never on the line together)");
  };
  for (const auto& f : r.followers)
    std::fprintf(out,
                 "  follower train %d behind train %d: %s; least separation margin %s, %s m "
                 "beyond the braking distance (its planned run: %s; the plan: %s)\n",
                 f.train + 1, f.behind + 1, f.affected ? "HELD UP" : "not affected",
                 kmh(f.min_speed_margin_kmh).c_str(),
                 std::isfinite(f.min_distance_margin_m)
                     ? data::format_number(std::round(f.min_distance_margin_m * 10) / 10).c_str()
                     : "inf",
                 kmh(f.planned_run_margin_kmh).c_str(), kmh(f.plan_margin_kmh).c_str());
  std::fflush(out);
}

void run_delay(const DelayArgs& a) {
  if (a.reference == !a.plan_file.empty()) bad("--plan/--reference", "exactly one of them");
  if (a.station.empty()) bad("--station", "the station the train leaves late");
  if (!std::isfinite(a.delay_s) || a.delay_s < 0.0 || a.delay_s > recovery::kMaxDelay_s)
    bad("--delay", "a delay in seconds, 0 <= D <= " + data::format_number(recovery::kMaxDelay_s) +
                       " (a longer one is a disruption, not a delay to recover); got " +
                       data::format_number(a.delay_s));
  if (a.train < 1) bad("--train", "a train number >= 1");
  if (a.followers < 0 || a.followers > 1000) bad("--followers", "0 to 1000 followers");
  if (!(a.frontier_span_s >= 10.0 && a.frontier_span_s <= 600.0))
    bad("--frontier-span", "a span in [10, 600] s");
  check_output_targets(
      {{"--json", a.json, false}, {"--csv", a.csv, false}, {"--svg", a.svg, true}});
  if (!a.svg.empty() && output::plot_format_for(a.svg) != output::PlotFormat::Svg)
    bad("--svg", "a file ending in .svg; got '" + a.svg + "'");
  recovery::DelayRecoveryOptions options;
  options.min_dwell_s = a.min_dwell_s;
  options.max_followers = a.followers;
  options.check_followers = a.followers > 0;
  options.lateness_first = a.lateness_first;
  options.recover_followers = !a.followers_wait;
  require_valid(options);
  const Problem p = load_fleet_problem(a.problem, "--train-file");
  // The plan first: a bad file fails before any engine is built.
  recovery::PlanStops ps =
      recovery::read_plan_stops(p.line, a.reference ? std::string() : a.plan_file);
  recovery::Plan& plan = ps.plan;
  const std::vector<std::string>& stops = ps.stops;
  const auto it = std::find(stops.begin(), stops.end(), a.station);
  if (it == stops.end())
    bad("--station", "a station of the plan (" + stops.front() + " .. " + stops.back() +
                         "); got '" + a.station + "'");
  const std::size_t station = static_cast<std::size_t>(it - stops.begin());
  if (station + 1 == stops.size())
    bad("--station", "a station the train departs from (not the last, " + stops.back() + ")");
  const std::unique_ptr<dp::SectionLibrary> lib =
      plan_library(p, a.problem, stops, a.frontier_span_s);
  const dp::SectionLibrary& library = *lib;
  if (a.reference) plan = recovery::reference_plan_on(library, stops);
  if (static_cast<std::size_t>(a.train) > plan.trains.size())
    bad("--train", "a train from 1 to " + std::to_string(plan.trains.size()) + "; got " +
                       std::to_string(a.train));
  StageProgress progress("ecorail delay", a.quiet);
  options.progress = progress.callback();
  output::FileFrontierStore store(cache_directory(a.cache_dir));
  if (!a.reference) options.plan_file = a.plan_file;
  const recovery::DelayRecoveryResult r =
      recovery::recover_delay(library, plan, static_cast<std::size_t>(a.train - 1), station,
                              a.delay_s, options, a.no_cache ? nullptr : &store);
  OutputOptions streams;
  streams.json = a.json;
  streams.csv = a.csv;
  streams.plot = a.svg;
  std::FILE* out = report_stream(streams);
  print_report(out, r, a.full_report);
  nlohmann::json report =
      recovery::delay_report_json(r, plan, a.train, a.reference ? "reference" : a.plan_file);
  report["provenance"] = run_provenance(p, a.problem,
                                        {{"plan", a.reference ? "reference" : a.plan_file},
                                         {"train_number", a.train},
                                         {"station", a.station},
                                         {"delay_s", a.delay_s},
                                         {"min_dwell_s", a.min_dwell_s},
                                         {"followers", a.followers},
                                         {"frontier_span_s", a.frontier_span_s}});
  data::OutputBatch batch;
  if (!a.json.empty()) batch.add(a.json, [&](std::ostream& o) { o << report.dump(2) << "\n"; });
  if (!a.csv.empty())
    batch.add(a.csv, [&](std::ostream& o) { recovery::write_delay_sections_csv(o, r); });
  if (!a.svg.empty() && !r.recovery_trip.empty()) {
    std::vector<std::string> names;
    for (const auto& s : r.sections) names.push_back(s.from);
    names.push_back(r.sections.back().to);
    output::SpeedPlotLabels labels;
    labels.stations = names;
    char title[300];
    std::snprintf(title, sizeof title,
                  "Train %d, %.0f s late at %s: exact recovery %.0f kJ (rule %.0f kJ, plan %.0f "
                  "kJ)",
                  a.train, a.delay_s, a.station.c_str(), r.summary.recovery_energy_kJ,
                  r.summary.rule_energy_kJ, r.summary.plan_energy_kJ);
    const output::Timeline timeline = output::trip_timeline(r.recovery_trip);
    batch.add_produced(a.svg, [&](const std::filesystem::path& f) {
      output::write_speed_plot_file(f, timeline, title, labels, output::PlotFormat::Svg);
    });
  }
  batch.commit();
}

}  // namespace

void add_delay_command(CLI::App& app) {
  auto args = std::make_shared<DelayArgs>();
  CLI::App* cmd = app.add_subcommand(
      "delay", "recover a late departure: back on time first, then least energy");
  add_plan_source_options(cmd, args->plan_file, args->reference);
  cmd->add_option("--train", args->train, "the late train (1-based, in departure order)")
      ->required();
  cmd->add_option("--station", args->station, "the station it leaves late")->required();
  cmd->add_option("--delay", args->delay_s, "how late it leaves (s)")->required();
  cmd->add_option("--min-dwell", args->min_dwell_s, "shortest dwell at a stop (s)")
      ->capture_default_str();
  cmd->add_option("--followers", args->followers,
                  "followers checked for separation at most (0: none)")
      ->capture_default_str();
  cmd->add_flag("--lateness-first", args->lateness_first,
                "least total lateness of the late train and its followers first, then energy");
  cmd->add_flag("--followers-wait", args->followers_wait,
                "held-up followers only wait and run their plan (not driven back on time)");
  add_plan_engine_options(cmd, args->problem, args->frontier_span_s, args->cache_dir,
                          args->no_cache);
  cmd->add_flag("--full-report", args->full_report, "print the full report");
  cmd->add_flag("--quiet", args->quiet, "no progress on stderr");
  cmd->add_option("--json", args->json, "write the recovery as JSON ('-': standard output)");
  cmd->add_option("--csv", args->csv, "write the recovery sections as CSV ('-': standard output)");
  cmd->add_option("--svg", args->svg, "write the recovery's speed profile (SVG)");
  cmd->callback([args] { run_delay(*args); });
}

}  // namespace ecorail::cli
