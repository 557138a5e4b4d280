// ecorail.delay.recover and ecorail.montecarlo on the 2.1 reference plan, a thin wrapper over
// the library the program's `delay` and `montecarlo --reference` call: a dp::SectionLibrary of
// the line's sections with frontiers (as cli/plan_input's plan_library), recovery::reference_plan,
// recovery::recover_delay; recovery::SectionRuns, recovery::MonteCarlo::run_days,
// recovery::summarise and recovery::run_json (montecarlo's to_dict, the program's --json). Plans
// from a timetable CSV (--plan) are the program's for now (docs/python.md).
#include <chrono>
#include <cmath>
#include <filesystem>

#include "data/route_builder.hpp"
#include "data/train_io.hpp"
#include "dp/section_library.hpp"
#include "output/frontier_cache.hpp"
#include "output/section_run_cache.hpp"
#include "python/src/common.hpp"
#include "recovery/delay_recovery.hpp"
#include "recovery/monte_carlo.hpp"
#include "recovery/monte_carlo_stats.hpp"
#include "recovery/plan.hpp"
#include "recovery/section_runs.hpp"

namespace ecorail::python {

namespace {

struct ReferencePlan {
  std::vector<std::string> stops;
  std::unique_ptr<dp::SectionLibrary> library;
  recovery::Plan plan;
};

// The library and the 2.1 reference plan, as the program makes them for --reference.
ReferencePlan reference_plan(const PyLine& line, const PyTrain& train, const EngineArgs& engine,
                             double frontier_span_s) {
  if (!(frontier_span_s >= 10.0 && frontier_span_s <= 600.0)) {
    bad_argument("frontier_span_s", "a span in [10, 600] s", std::to_string(frontier_span_s));
  }
  if (train.train.has_efficiency_maps()) {
    bad_argument("train", "a train with constant efficiencies for the fleet models",
                 "'" + train.train.name + "'");
  }
  ReferencePlan r;
  r.stops = data::stops_between(line.line, line.line.stations.front().name,
                                line.line.stations.back().name);
  dp::SectionLibraryOptions options;
  options.engine = engine_options(engine, train);
  options.frontier_span_s = frontier_span_s;
  require_valid(options);
  char key[200];
  std::snprintf(key, sizeof key, "delay|%016llx|%016llx|%s",
                static_cast<unsigned long long>(line.line.checksum()),
                static_cast<unsigned long long>(data::train_checksum(train.train)),
                line.line.curve_formula == data::CurveFormula::Roeckl ? "roeckl" : "600/R");
  {
    py::gil_scoped_release release;
    r.library = std::make_unique<dp::SectionLibrary>(
        train.train, data::build_routes(line.line, r.stops, train.train), options, key);
    dp::JourneyOptions journey;
    journey.engine = options.engine;
    journey.measure_marginals = false;
    r.plan = recovery::reference_plan(*r.library, r.stops, journey);
  }
  return r;
}

// The frontier cache the program uses (cache=True): cache_dir, or the program's default
// directory ($XDG_CACHE_HOME/ecorail/frontiers) when it is None; cached entries are keyed by
// line, train, grid and engine version and never trusted when stale.
std::filesystem::path cache_directory(const py::object& cache_dir) {
  if (cache_dir.is_none()) return output::FileFrontierStore::default_directory();
  return std::string(py::str(py::module_::import("os").attr("fspath")(cache_dir)));
}

struct PyRecovery {
  recovery::DelayRecoveryResult result;
  PySummary summary;
};

PyRecovery recover_py(const PyLine& line, const PyTrain& train, int train_number,
                      const std::string& station, double delay_s, double min_dwell_s, int followers,
                      double frontier_span_s, double ds_m, double dv_kmh, int threads, bool cache,
                      const py::object& cache_dir) {
  if (!std::isfinite(delay_s) || delay_s < 0.0 || delay_s > 86400.0) {
    bad_argument("delay_s", "a delay in seconds, 0 <= D <= 86400", std::to_string(delay_s));
  }
  if (train_number < 1)
    bad_argument("train_number", "a train number >= 1", std::to_string(train_number));
  if (followers < 0 || followers > 1000)
    bad_argument("followers", "0 to 1000 followers", std::to_string(followers));
  recovery::DelayRecoveryOptions options;
  options.min_dwell_s = min_dwell_s;
  options.max_followers = followers;
  options.check_followers = followers > 0;
  require_valid(options);
  ReferencePlan r =
      reference_plan(line, train, {ds_m, dv_kmh, "traction", "hold", threads}, frontier_span_s);
  const auto it = std::find(r.stops.begin(), r.stops.end(), station);
  if (it == r.stops.end() || it + 1 == r.stops.end()) {
    bad_argument("station",
                 "a station the train departs from (" + r.stops.front() + " .. " +
                     r.stops[r.stops.size() - 2] + ")",
                 "'" + station + "'");
  }
  if (static_cast<std::size_t>(train_number) > r.plan.trains.size()) {
    bad_argument("train_number", "a train from 1 to " + std::to_string(r.plan.trains.size()),
                 std::to_string(train_number));
  }
  const std::filesystem::path dir = cache_directory(cache_dir);
  output::FileFrontierStore store(dir);
  PyRecovery out;
  try {
    py::gil_scoped_release release;
    out.result = recovery::recover_delay(*r.library, r.plan, std::size_t(train_number - 1),
                                         std::size_t(it - r.stops.begin()), delay_s, options,
                                         cache ? &store : nullptr);
  } catch (const recovery::DelayInputError& e) {
    bad_argument(e.field(), "input the recovery can use", e.what());
  }
  const auto& s = out.result.summary;
  out.summary = {s.termination, s.BriefReport(), s.FullReport(), s.warnings};
  return out;
}

struct PyMonteCarlo {
  nlohmann::json report;
  recovery::MonteCarloStatistics statistics;
  PySummary summary;
  std::vector<double> traction_kJ, substation_kJ;
};

PyMonteCarlo montecarlo_py(const PyLine& line, const PyTrain& train, int days, std::int64_t seed,
                           const std::string& recovery_name, const std::string& tail,
                           double early_s, double run_early_s, double min_dwell_s,
                           double takeover_s, double punctual_s, double separation_s,
                           double knot_step_s, double step_s, double frontier_span_s, double ds_m,
                           double dv_kmh, int threads, bool cache, const py::object& cache_dir,
                           const py::object& progress) {
  if (days < 1 || days > 100000000)
    bad_argument("days", "a number of days from 1 to 1e8", std::to_string(days));
  if (seed < 0) bad_argument("seed", "a seed >= 0", std::to_string(seed));
  recovery::MonteCarloOptions o;
  if (recovery_name == "exact") {
    o.recovery = recovery::RecoveryPolicy::Exact;
  } else if (recovery_name == "rule") {
    o.recovery = recovery::RecoveryPolicy::Rule;
  } else if (recovery_name == "exact-punctual") {
    o.recovery = recovery::RecoveryPolicy::ExactPunctual;
  } else {
    bad_argument("recovery", "'exact', 'exact-punctual' or 'rule'", "'" + recovery_name + "'");
  }
  std::string why;
  if (!recovery::parse_delay_tail(tail, o.delays, &why)) bad_argument("tail", "a delay tail", why);
  o.seed = static_cast<std::uint64_t>(seed);
  o.early_s = early_s;
  o.run_early_s = run_early_s;
  o.min_dwell_s = min_dwell_s;
  o.takeover_s = takeover_s;
  o.punctual_s = punctual_s;
  o.separation_s = separation_s;
  o.knot_step_s = knot_step_s;
  o.bin_step_s = step_s;
  require_valid(o);
  const EngineArgs engine{ds_m, dv_kmh, "traction", "hold", threads};
  ReferencePlan r = reference_plan(line, train, engine, frontier_span_s);
  const std::filesystem::path dir = cache_directory(cache_dir);
  output::FileFrontierStore store(dir);
  output::FileSectionRunStore run_store(dir / "section-runs");
  Interruptible guard(progress);
  const dp::ProgressFn check = guard.callback();
  const auto wall0 = std::chrono::steady_clock::now();
  PyMonteCarlo out;
  guard.run([&] {
    recovery::SectionRuns runs(*r.library, cache ? &store : nullptr, o.knot_step_s, o.bin_step_s,
                               cache ? &run_store : nullptr);
    const recovery::MonteCarlo mc(*r.library, r.plan, o, runs);
    const recovery::DayRecord plan_day = mc.plan_day();
    std::vector<recovery::DayRecord> records =
        mc.run_days(0, static_cast<std::uint64_t>(days), threads,
                    [&](int done, int total) { check("day", done, total); });
    recovery::MonteCarloRun run;
    run.stations = r.plan.stations;
    run.histogram = recovery::pooled_histogram(records);
    run.days = std::move(records);
    run.plan_energy = {{"traction_kJ", plan_day.traction_kJ},
                       {"substation_kJ", plan_day.substation_kJ},
                       {"used_regen_kJ", plan_day.used_regen_kJ},
                       {"regen_kJ", plan_day.regen_kJ}};
    run.config = {{"plan", "reference"},
                  {"trains", r.plan.trains.size()},
                  {"days", days},
                  {"seed", seed},
                  {"recovery", recovery_name},
                  {"p_none", o.delays.p_none},
                  {"p_small", o.delays.p_small},
                  {"small_max_s", o.delays.small_max_s},
                  {"tail", o.delays.tail_text()},
                  {"early_s", o.early_s},
                  {"run_early_s", o.run_early_s},
                  {"min_dwell_s", o.min_dwell_s},
                  {"takeover_s", o.takeover_s},
                  {"punctual_s", o.punctual_s},
                  {"on_time_tolerance_s", o.on_time_tolerance_s},
                  {"separation_s", mc.separation_s()},
                  {"knot_step_s", o.knot_step_s},
                  {"bin_step_s", o.bin_step_s},
                  {"frontier_span_s", frontier_span_s},
                  {"ds_m", ds_m},
                  {"dv_kmh", dv_kmh},
                  {"line_checksum", std::to_string(line.line.checksum())},
                  {"train_checksum", std::to_string(data::train_checksum(train.train))}};
    out.statistics = recovery::summarise(run.days, run.histogram);
    out.report = recovery::run_json(run, "");
    for (const auto& d : run.days) {
      out.traction_kJ.push_back(d.traction_kJ);
      out.substation_kJ.push_back(d.substation_kJ);
    }
    recovery::MonteCarloSummary sm;
    sm.termination = dp::Termination::CONVERGENCE;
    sm.first_day = 0;
    sm.last_day = static_cast<std::uint64_t>(days);
    sm.threads = threads;
    sm.separation_s = mc.separation_s();
    sm.section_runs = runs.piece_count();
    sm.statistics = out.statistics;
    sm.plan_traction_kJ = plan_day.traction_kJ;
    sm.plan_substation_kJ = plan_day.substation_kJ;
    sm.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
    out.summary = {sm.termination, sm.BriefReport(), sm.FullReport(), {}};
    return 0;
  });
  return out;
}

py::dict estimate_dict(const recovery::Estimate& e) {
  py::dict d;
  d["mean"] = e.mean;
  d["sd"] = e.sd;
  d["ci95_half_width"] = e.ci95;
  d["days"] = e.n;
  return d;
}

}  // namespace

void bind_delay(py::module_& m) {
  py::module_ delay = m.def_submodule("delay", "Late departures recovered (question 3.1).");
  py::class_<PyRecovery>(delay, "Recovery",
                         "A late departure recovered: back on time at the earliest station, then "
                         "the least traction energy (kJ) over the recovery sections, beside the "
                         "seed paper's rule.")
      .def_readonly("summary", &PyRecovery::summary)
      .def_property_readonly("recovered",
                             [](const PyRecovery& r) { return r.result.summary.recovered; })
      .def_property_readonly("back_on_time_at",
                             [](const PyRecovery& r) { return r.result.summary.back_on_time_at; })
      .def_property_readonly("final_lateness_s",
                             [](const PyRecovery& r) { return r.result.summary.final_lateness_s; })
      .def_property_readonly(
          "recovery_energy_kJ",
          [](const PyRecovery& r) { return r.result.summary.recovery_energy_kJ; })
      .def_property_readonly("rule_energy_kJ",
                             [](const PyRecovery& r) { return r.result.summary.rule_energy_kJ; })
      .def_property_readonly("plan_energy_kJ",
                             [](const PyRecovery& r) { return r.result.summary.plan_energy_kJ; })
      .def_property_readonly(
          "sections",
          [](const PyRecovery& r) {
            py::list list;
            for (const auto& s : r.result.sections) {
              py::dict d;
              d["from"] = s.from;
              d["to"] = s.to;
              d["min_time_s"] = s.min_time_s;
              d["planned_time_s"] = s.planned_time_s;
              d["new_time_s"] = s.new_time_s;
              d["rule_time_s"] = s.rule_time_s;
              d["plan_energy_kJ"] = s.plan_energy_kJ;
              d["new_energy_kJ"] = s.new_energy_kJ;
              d["rule_energy_kJ"] = s.rule_energy_kJ;
              d["flat_out"] = s.flat_out;
              d["new_arrival_s"] = s.new_arrival_s;
              d["planned_arrival_s"] = s.planned_arrival_s;
              list.append(d);
            }
            return list;
          },
          "One dict per recovery section: times in s, energies in kJ.");
  delay.def(
      "recover", &recover_py, py::arg("line"), py::arg("train"), py::kw_only(),
      py::arg("train_number"), py::arg("station"), py::arg("delay_s"),
      py::arg("min_dwell_s") = 30.0, py::arg("followers") = 5, py::arg("frontier_span_s") = 60.0,
      py::arg("ds_m") = 5.0, py::arg("dv_kmh") = 0.2, py::arg("threads") = 0,
      py::arg("cache") = true, py::arg("cache_dir") = py::none(),
      "Train train_number (1-based) of the 2.1 reference plan leaves station delay_s "
      "seconds late, as `ecorail delay --reference`: back on time at the earliest station "
      "(dwells not below min_dwell_s), then the exact least-energy split; followers (at "
      "most this many) checked under the braking-distance cap. cache: use the program's frontier "
      "cache (cache_dir, or its default directory when None).");

  py::class_<PyMonteCarlo>(m, "MonteCarloResult",
                           "Service days under random delays: punctuality, lateness, recovery "
                           "time, traction and substation energy (kJ) with 95 % confidence "
                           "intervals.")
      .def_readonly("summary", &PyMonteCarlo::summary)
      .def(
          "to_dict", [](const PyMonteCarlo& r) { return to_python(r.report); },
          "The document `ecorail montecarlo --reference --json` writes.")
      .def_property_readonly("days", [](const PyMonteCarlo& r) { return r.statistics.days; })
      .def_property_readonly(
          "punctuality",
          [](const PyMonteCarlo& r) { return estimate_dict(r.statistics.punctuality); },
          "Share of punctual arrivals per day: mean and 95 % interval.")
      .def_property_readonly(
          "mean_lateness_s",
          [](const PyMonteCarlo& r) { return estimate_dict(r.statistics.mean_lateness_s); })
      .def_property_readonly(
          "substation_energy_kJ",
          [](const PyMonteCarlo& r) { return estimate_dict(r.statistics.substation_kJ); })
      .def_property_readonly(
          "traction_energy_kJ",
          [](const PyMonteCarlo& r) { return estimate_dict(r.statistics.traction_kJ); })
      .def_property_readonly(
          "day_traction_kJ", [](const PyMonteCarlo& r) { return to_numpy(r.traction_kJ); },
          "Traction energy of each day, kJ (float64).")
      .def_property_readonly(
          "day_substation_kJ", [](const PyMonteCarlo& r) { return to_numpy(r.substation_kJ); },
          "Substation energy of each day, kJ (float64).");
  m.def("montecarlo", &montecarlo_py, py::arg("line"), py::arg("train"), py::kw_only(),
        py::arg("days") = 100, py::arg("seed") = 1, py::arg("recovery") = "exact",
        py::arg("tail") = "exponential:30", py::arg("early_s") = 10.0, py::arg("run_early_s") = 0.0,
        py::arg("min_dwell_s") = 30.0, py::arg("takeover_s") = 120.0, py::arg("punctual_s") = 10.0,
        py::arg("separation_s") = -1.0, py::arg("knot_step_s") = 1.0, py::arg("step_s") = 0.1,
        py::arg("frontier_span_s") = 60.0, py::arg("ds_m") = 5.0, py::arg("dv_kmh") = 0.2,
        py::arg("threads") = 0, py::arg("cache") = true, py::arg("cache_dir") = py::none(),
        py::arg("progress") = py::none(),
        "Whole service days of the 2.1 reference plan under random delays, as `ecorail "
        "montecarlo --reference`: days from seed (counter-based draws; the same bytes for any "
        "threads), recovery 'exact', 'exact-punctual' or 'rule', delay tail e.g. "
        "'exponential:30'; times in s. cache: the program's frontier and section-run cache "
        "(cache_dir, or its default directory when None), shared with `ecorail montecarlo`.");
}

}  // namespace ecorail::python
