// `ecorail timetable evaluate|optimise`: fleet timetables that use regenerated braking energy
// (question 2.1). Parses the flags (cli/timetable_options.hpp), runs fleet::TimetableStudy,
// prints its summaries and hands its results to the output writers.
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "cli/commands.hpp"
#include "cli/timetable_options.hpp"
#include "data/atomic_file.hpp"
#include "data/csv_reader.hpp"
#include "data/input_error.hpp"
#include "energy/model_registry.hpp"
#include "fleet/timetable_study.hpp"
#include "output/fleet_outputs.hpp"
#include "output/timetable_json.hpp"

namespace ecorail::cli {

namespace {

void print_energy(const energy::FleetEvaluation& ev, const char* what) {
  if (ev.network) {
    const power::NetworkEvaluation& n = *ev.network;
    std::printf(
        "%s (network, step %s s): substations %.1f kJ + used regen %.1f kJ = traction input "
        "%.1f kJ + auxiliaries %.1f kJ + line losses %.1f kJ; regen curtailed %.1f kJ of %.1f "
        "kJ, traction curtailed %.1f kJ; train voltage %.1f to %.1f V\n",
        what, data::format_number(ev.time_step_s).c_str(), n.substation_J / 1e3,
        n.used_regen_J / 1e3, n.traction_input_J / 1e3, n.auxiliary_J / 1e3, n.line_losses_J / 1e3,
        n.curtailed_regen_J / 1e3, n.regen_J / 1e3, n.curtailed_traction_J / 1e3,
        n.min_train_voltage_V, n.max_train_voltage_V);
    return;
  }
  std::printf(
      "%s (%s%s%s): substation %.1f kJ = traction %.1f kJ - used regen %.1f kJ (of %.1f kJ "
      "regenerated, %.2f %%)\n",
      what, ev.model.c_str(), ev.overlap_variant.empty() ? "" : (", " + ev.overlap_variant).c_str(),
      ev.time_step_s > 0.0 ? (", step " + data::format_number(ev.time_step_s) + " s").c_str() : "",
      ev.total.substation_J() / 1e3, ev.total.traction_J / 1e3, ev.total.used_regen_J / 1e3,
      ev.total.regen_J / 1e3,
      ev.total.regen_J > 0 ? 100.0 * ev.total.used_regen_J / ev.total.regen_J : 0.0);
}

void write_outputs(const TimetableArgs& a, const fleet::TimetableStudy& s,
                   const energy::FleetEvaluation& ev, nlohmann::json energy) {
  output::FleetTimetable tt{s.stops(),        s.positions_m(),          ev.departures_s,
                            s.pattern().trip, s.problem().peak_windows, s.per_train_trips()};
  const auto [w0, w1] = parse_range(a.window, "--window");
  data::OutputBatch batch;
  // The separation check first: it adds to the energy JSON (the batch writes on add).
  if (a.service.wanted() && !s.per_train_patterns().empty())
    bad("--separation", "one pattern for every train (not --per-train-patterns)");
  const auto service_run = run_service_check(a.service, s.library(), s.pattern().pattern,
                                             ev.departures_s, energy, batch);
  if (!a.json.empty()) batch.add(a.json, [&](std::ostream& o) { o << energy.dump(2) << "\n"; });
  if (!a.gtfs.gtfs.empty()) {
    // trip_id "train-001" ...: zero-padded so that the trips sort in departure order.
    const int width = static_cast<int>(std::to_string(ev.departures_s.size()).size());
    std::vector<std::pair<std::string, physics::Trip>> trips;
    for (std::size_t k = 0; k < ev.departures_s.size(); ++k) {
      std::string number = std::to_string(k + 1);
      number.insert(0, width - number.size(), '0');
      trips.emplace_back("train-" + number, tt.train_trip(k));
    }
    add_gtfs_outputs(batch, a.gtfs, trips, s.line());
  }
  if (!a.csv.empty())
    batch.add(a.csv, [&](std::ostream& o) { output::write_timetable_csv(o, tt); });
  if (!a.xlsx.empty())
    batch.add_produced(a.xlsx, [&](const std::filesystem::path& f) {
      output::write_timetable_xlsx(f, tt, energy);
    });
  const std::string model = energy.value("model", "");
  if (!a.diagram.empty())
    batch.add_produced(a.diagram, [&](const std::filesystem::path& f) {
      output::write_train_diagram(f, *output::plot_format_for(a.diagram), tt, w0, w1,
                                  "Train diagram, " + std::to_string(ev.departures_s.size()) +
                                      " trains (" + model + " model)");
    });
  if (!a.voltage_plot.empty()) {
    std::vector<int> ids;
    const auto flow = s.load_flow_at(ev.departures_s, a.voltage_at_s, &ids);
    batch.add_produced(a.voltage_plot, [&, flow, ids](const std::filesystem::path& f) {
      output::write_voltage_plot(f, *output::plot_format_for(a.voltage_plot), flow,
                                 *s.model_options().power_supply, ids,
                                 "Line voltage at " + output::clock_text(a.voltage_at_s) + " (" +
                                     data::format_number(a.voltage_at_s) + " s)");
    });
  }
  if (!a.power_plot.empty() && s.has_network()) {
    const auto trace = s.substation_trace(ev.departures_s, w0, w1);
    batch.add_produced(a.power_plot, [&, trace](const std::filesystem::path& f) {
      output::write_substation_plot(f, *output::plot_format_for(a.power_plot), trace,
                                    "Substation power (network model)");
    });
  } else if (!a.power_plot.empty()) {
    if (!s.has_power_trace())
      bad("--power-plot", "a power-flow or sections model (the overlap model has no power trace)");
    const auto trace = s.power_trace(ev.departures_s, w0, w1);
    batch.add_produced(a.power_plot, [&](const std::filesystem::path& f) {
      output::write_power_plot(f, *output::plot_format_for(a.power_plot), trace,
                               "Fleet power (" + model + " model)");
    });
  }
  batch.commit();
}

void run_evaluate(const TimetableArgs& a) {
  // The departures are checked before the line's sections are built: a bad file fails fast.
  const std::vector<int> departures = read_departures(a, fleet_problem(a));
  const fleet::TimetableStudy s = make_study(a);
  const fleet::StudyEvaluation e = s.evaluate(departures);  // throws before anything is printed
  print_energy(e.evaluation, "timetable evaluate");
  if (e.substation_without_reuse_J && e.evaluation.network) {
    const double off = *e.substation_without_reuse_J;
    std::printf(
        "  without regeneration the substations would supply %.1f kJ: reuse saves %.1f kJ\n",
        off / 1e3, (off - e.evaluation.network->substation_J) / 1e3);
  }
  write_outputs(a, s, e.evaluation, output::timetable_evaluation_json(s, e));
}

void run_optimise(const TimetableArgs& a) {
  fleet::StudyOptimiseOptions so = a.search;
  if (so.per_train_patterns) {
    // Per-train patterns are a pattern optimisation: the flag implies --optimise pattern.
    if (a.optimise_given && a.optimise != "pattern")
      bad("--per-train-patterns", "--optimise pattern (per-train patterns re-time each train)");
    if (energy::is_energy_model(a.model) && !energy::model_inputs(a.model).per_train_trips)
      bad("--per-train-patterns",
          "--model " + energy::models_with(&energy::ModelInputs::per_train_trips) +
              " (the per-train search prices one train's pattern against the fleet's power "
              "balance; the overlap model has none and the network balance lays one trip under "
              "every train); got '" +
              a.model + "'");
  }
  if (a.optimise != "headways" && a.optimise != "pattern")
    bad("--optimise", "headways or pattern; got '" + a.optimise + "'");
  so.pattern = a.optimise == "pattern" || so.per_train_patterns;
  fleet::HeadwayOptimiserOptions& o = so.headways;
  o.threads = a.problem.threads;
  require_valid_flags(o, {{"restarts", "--restarts"},
                          {"rounds", "--rounds"},
                          {"moves_per_run", "--moves"},
                          {"time_limit_s", "--time-limit"},
                          {"gap_fraction", "--gap"},
                          {"anneal_step_s", "--anneal-step"},
                          {"threads", "--threads"}});
  const bool given = !a.headways_file.empty() || !a.departures_file.empty();
  if (given && so.pattern)
    bad(a.headways_file.empty() ? "--departures" : "--headways",
        "--optimise headways (a given timetable is a start for the headway search, whose "
        "pattern is fixed)");
  // Read before the sections are built: a bad file is refused at once.
  if (given) o.given_starts_s = {read_departures(a, fleet_problem(a))};
  fleet::TimetableStudy s = make_study(a);
  if (!a.quiet && isatty(STDERR_FILENO)) {
    o.progress = [](const fleet::OptimiserProgress& p) {
      // Before the first start is priced there is no best yet; "\033[K" clears what a longer
      // line before left.
      char best[64] = "no timetable yet", bound[64] = "";
      if (p.best_used_J > 0.0)
        std::snprintf(best, sizeof best, "best used %.1f kJ", p.best_used_J / 1e3);
      if (std::isfinite(p.bound_used_J))
        std::snprintf(bound, sizeof bound, ", bound %.1f kJ", p.bound_used_J / 1e3);
      std::fprintf(stderr, "\r  %-26s %s%s, %.1f s\033[K", p.stage.c_str(), best, bound,
                   p.elapsed_s);
      std::fflush(stderr);
    };
    so.pattern_progress = [](const fleet::PatternProgress& p) {
      std::fprintf(stderr, "\r  %-26s %d moves of %d priced, substation %.1f kJ, %.1f s   ",
                   (p.stage + " moves").c_str(), p.moves_accepted, p.patterns_evaluated,
                   p.substation_J / 1e3, p.elapsed_s);
      std::fflush(stderr);
    };
  }
  const fleet::StudyOptimisation r = s.optimise(so);
  // A timetable the model found no solution for is never a result: nothing is printed.
  if (!r.result.summary.IsSolutionUsable())
    throw std::runtime_error("the optimiser failed: " + r.result.summary.message);
  if (o.progress) std::fprintf(stderr, "\n");
  if (r.pattern_search) {
    print_energy(r.pattern_search->headways_only, "headways alone, default pattern");
    std::printf("  %s\n", r.pattern_search->BriefReport().c_str());
  }
  print_energy(r.result.evaluation, "timetable optimise");
  std::printf("  %s\n", r.result.summary.BriefReport().c_str());
  if (a.full_report) std::printf("%s", r.result.summary.FullReport().c_str());
  write_outputs(a, s, r.result.evaluation, output::timetable_optimisation_json(s, r, o.seed));
}

}  // namespace

void add_timetable_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("timetable", "fleet timetables that use regenerated energy");
  cmd->require_subcommand(1);
  static TimetableArgs eval_args, opt_args;
  auto* ev = cmd->add_subcommand("evaluate", "energy of a given timetable (default: uniform)");
  add_fleet_options(ev, eval_args);
  ev->add_option("--headways", eval_args.headways_file, "CSV with a column headway_s");
  ev->add_option("--departures", eval_args.departures_file, "CSV with a column departure_s");
  ev->add_flag("--uniform", eval_args.uniform, "uniform headways (the default)");
  ev->add_option("--nearest", eval_args.nearest,
                 "with --peak: the timetable nearest (least squares) to class headways "
                 "PEAK:OFFPEAK (s), e.g. 149:331.5");
  input_files(ev, {"--headways", "--departures", "--power-supply"});
  ev->callback([] { run_evaluate(eval_args); });
  auto* op = cmd->add_subcommand("optimise", "headways that minimise the substation energy");
  add_fleet_options(op, opt_args);
  op->add_option("--seed", opt_args.search.headways.seed, "random seed")->capture_default_str();
  op->add_option("--time-limit", opt_args.search.headways.time_limit_s,
                 "seconds of the whole search, polish included (0: none)")
      ->capture_default_str();
  op->add_option("--gap", opt_args.search.headways.gap_fraction,
                 "CONVERGENCE only when the proven gap is within this fraction of the substation "
                 "energy")
      ->capture_default_str();
  op->add_option("--restarts", opt_args.search.headways.restarts, "annealing runs per start")
      ->capture_default_str();
  op->add_option("--moves", opt_args.search.headways.moves_per_run, "annealing moves per run")
      ->capture_default_str();
  op->add_option("--rounds", opt_args.search.headways.rounds,
                 "further annealing rounds after the first when no --time-limit is given (with "
                 "one, rounds run until it)")
      ->capture_default_str();
  op->add_option("--anneal-step", opt_args.search.headways.anneal_step_s,
                 "time step of the annealing (s)")
      ->capture_default_str();
  op->add_option("--optimise", opt_args.optimise,
                 "headways (pattern fixed) or pattern (dwells and running times too)")
      ->capture_default_str();
  op->add_flag("--per-train-patterns", opt_args.search.per_train_patterns,
               "each train its own dwells and running times (implies --optimise pattern; "
               "power-flow and sections models)");
  op->add_option("--headways", opt_args.headways_file,
                 "a timetable to start from too, CSV with a column headway_s (the result never "
                 "uses less regenerated energy)");
  op->add_option("--departures", opt_args.departures_file,
                 "a timetable to start from too, CSV with a column departure_s");
  input_files(op, {"--headways", "--departures", "--power-supply"});
  op->callback([op] {
    opt_args.optimise_given = op->get_option("--optimise")->count() > 0;
    run_optimise(opt_args);
  });
}

}  // namespace ecorail::cli
