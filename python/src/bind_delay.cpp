// ecorail.delay.recover, ecorail.montecarlo and ecorail.delay.Plan: a thin wrapper over the
// library the program's `delay` and `montecarlo` call. The plan is the 2.1 reference plan, a
// timetable CSV or a Plan object, set up by recovery/plan_source.hpp as the program sets it up
// (the section library of its stations, keyed for the frontier cache as the program's);
// recovery::recover_delay and recovery::delay_report_json (recover's to_dict, the program's
// --json), recovery::MonteCarlo and recovery::simulate_days / run_json (montecarlo's to_dict).
#include <chrono>
#include <cmath>
#include <filesystem>

#include "data/train_io.hpp"
#include "dp/section_library.hpp"
#include "output/frontier_cache.hpp"
#include "output/section_run_cache.hpp"
#include "output/solve_reports.hpp"
#include "python/src/common.hpp"
#include "recovery/delay_recovery.hpp"
#include "recovery/delay_report.hpp"
#include "recovery/monte_carlo.hpp"
#include "recovery/monte_carlo_run.hpp"
#include "recovery/monte_carlo_stats.hpp"
#include "recovery/plan.hpp"
#include "recovery/plan_source.hpp"
#include "recovery/section_runs.hpp"

namespace ecorail::python {

namespace {

// ecorail.delay.Plan: a timetable plan (stations in the order of travel, per train its arrival
// and departure clock times), with the name reports give it.
struct PyPlan {
  recovery::Plan plan;
  std::string name = "plan";  // the file it was read from, or what the caller named it
  std::string file;           // the file it was read from ("" when made in Python)
};

PyPlan plan_from_arrays(std::vector<std::string> stations, const py::array_t<double>& arrival_s,
                        const py::array_t<double>& departure_s, const std::string& name) {
  if (arrival_s.ndim() != 2 || departure_s.ndim() != 2 ||
      arrival_s.shape(0) != departure_s.shape(0) || arrival_s.shape(1) != departure_s.shape(1) ||
      arrival_s.shape(1) != static_cast<py::ssize_t>(stations.size())) {
    bad_argument("arrival_s/departure_s",
                 "two arrays of shape (trains, stations) with one column per station",
                 "shapes that differ");
  }
  PyPlan p;
  p.name = name;
  p.plan.stations = std::move(stations);
  const auto arr = arrival_s.unchecked<2>();
  const auto dep = departure_s.unchecked<2>();
  for (py::ssize_t k = 0; k < arr.shape(0); ++k) {
    recovery::TrainStops t;
    for (py::ssize_t j = 0; j < arr.shape(1); ++j) {
      t.arrival_s.push_back(arr(k, j));
      t.departure_s.push_back(dep(k, j));
    }
    p.plan.trains.push_back(std::move(t));
  }
  if (p.plan.trains.empty() || p.plan.stations.size() < 2) {
    bad_argument("arrival_s/departure_s", "at least one train and two stations", "none");
  }
  if (const std::string why = p.plan.problem(); !why.empty()) {
    bad_argument("arrival_s/departure_s", "a timetable that holds", why);
  }
  return p;
}

// A plan's arrival or departure times as an array of shape (trains, stations).
py::array_t<double> stop_times(const recovery::Plan& plan,
                               std::vector<double> recovery::TrainStops::*times) {
  py::array_t<double> a({plan.trains.size(), plan.stations.size()});
  auto v = a.mutable_unchecked<2>();
  for (std::size_t k = 0; k < plan.trains.size(); ++k)
    for (std::size_t j = 0; j < plan.stations.size(); ++j) v(k, j) = (plan.trains[k].*times)[j];
  return a;
}

// What a delay study runs on: the plan (None: the reference plan; a path: a timetable CSV; an
// ecorail.delay.Plan), its stations and their section library, as the program sets them up.
struct PlanSetup {
  std::vector<std::string> stops;
  std::unique_ptr<dp::SectionLibrary> library;
  recovery::Plan plan;
  std::string name;  // "reference", the file as given, or the Plan's name
  std::string file;  // the file it was read from, for errors about it ("" otherwise)
};

PlanSetup plan_setup(const PyLine& line, const PyTrain& train, const py::object& plan,
                     const EngineArgs& engine, double frontier_span_s) {
  check_range("frontier_span_s", frontier_span_s, 10.0, 600.0, "a span in [10, 600] s");
  check_fleet_train(train);
  PlanSetup r;
  bool reference = plan.is_none();
  if (reference) {
    r.name = "reference";
    r.stops = recovery::read_plan_stops(line.line, "").stops;
  } else if (py::isinstance<PyPlan>(plan)) {
    const PyPlan& p = plan.cast<const PyPlan&>();
    r.plan = p.plan;
    r.name = p.name;
    r.file = p.file;
    recovery::check_plan_stations(line.line, r.plan, p.file.empty() ? p.name : p.file);
    r.stops = r.plan.stations;
  } else {
    r.file = fspath(plan);
    r.name = r.file;
    recovery::PlanStops ps = recovery::read_plan_stops(line.line, r.file);
    r.plan = std::move(ps.plan);
    r.stops = std::move(ps.stops);
  }
  dp::SectionLibraryOptions options;
  options.engine = engine_options(engine, train);
  options.frontier_span_s = frontier_span_s;
  require_valid(options);
  py::gil_scoped_release release;
  r.library = recovery::plan_section_library(line.line, train.train, r.stops, options);
  if (reference) r.plan = recovery::reference_plan_on(*r.library, r.stops);
  return r;
}

// The frontier cache the program uses (cache=True): cache_dir, or the program's default
// directory ($XDG_CACHE_HOME/ecorail/frontiers) when it is None; cached entries are keyed by
// line, train, grid and engine version and never trusted when stale.
std::filesystem::path cache_directory(const py::object& cache_dir) {
  if (cache_dir.is_none()) return output::FileFrontierStore::default_directory();
  return fspath(cache_dir);
}

struct PyRecovery {
  recovery::DelayRecoveryResult result;
  PySummary summary;
  nlohmann::json report;  // the program's --json
};

PyRecovery recover_py(const PyLine& line, const PyTrain& train, int train_number,
                      const std::string& station, double delay_s, const py::object& plan,
                      double min_dwell_s, int followers, double frontier_span_s, double ds_m,
                      double dv_kmh, int threads, bool cache, const py::object& cache_dir) {
  check_range("delay_s", delay_s, 0.0, 86400.0, "a delay in seconds, 0 <= D <= 86400");
  check_count("train_number", train_number, 1, 1000000, "a train number >= 1");
  check_count("followers", followers, 0, 1000, "0 to 1000 followers");
  recovery::DelayRecoveryOptions options;
  options.min_dwell_s = min_dwell_s;
  options.max_followers = followers;
  options.check_followers = followers > 0;
  require_valid(options);
  PlanSetup r =
      plan_setup(line, train, plan, {ds_m, dv_kmh, "traction", "hold", threads}, frontier_span_s);
  options.plan_file = r.file;
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
  {
    py::gil_scoped_release release;
    out.result = recovery::recover_delay(*r.library, r.plan, std::size_t(train_number - 1),
                                         std::size_t(it - r.stops.begin()), delay_s, options,
                                         cache ? &store : nullptr);
  }
  out.summary = summary_of(out.result.summary, out.result.summary.warnings);
  out.report = recovery::delay_report_json(out.result, r.plan, train_number, r.name);
  output::RunInputs inputs = run_inputs(line, train, "", "", "traction", ds_m, dv_kmh);
  out.report["provenance"] = output::run_provenance_json(line.line, train.train, inputs,
                                                         {{"plan", r.name},
                                                          {"train_number", train_number},
                                                          {"station", station},
                                                          {"delay_s", delay_s},
                                                          {"min_dwell_s", min_dwell_s},
                                                          {"followers", followers},
                                                          {"frontier_span_s", frontier_span_s}});
  return out;
}

struct PyMonteCarlo {
  nlohmann::json report;
  recovery::MonteCarloStatistics statistics;
  PySummary summary;
  std::vector<double> traction_kJ, substation_kJ;
};

PyMonteCarlo montecarlo_py(const PyLine& line, const PyTrain& train, const py::object& plan,
                           long long days, std::int64_t seed, const std::string& recovery_name,
                           const std::string& followers, const std::string& tail, double early_s,
                           double run_early_s, double min_dwell_s, double takeover_s,
                           double punctual_s, double separation_s, double knot_step_s,
                           double step_s, double frontier_span_s, double ds_m, double dv_kmh,
                           int threads, bool cache, const py::object& cache_dir,
                           const py::object& progress) {
  check_count("days", days, 1, 100000000, "a number of days from 1 to 1e8");
  check_count("seed", seed, 0, INT64_MAX, "a seed >= 0");
  recovery::MonteCarloOptions o;
  const auto policy = recovery::recovery_policy_from_name(recovery_name);
  if (!policy) {
    bad_argument("recovery", "'exact', 'exact-punctual' or 'rule'", "'" + recovery_name + "'");
  }
  o.recovery = *policy;
  const auto model = recovery::follower_model_from_name(followers);
  if (!model) bad_argument("followers", "'driven' or 'shortcut'", "'" + followers + "'");
  o.followers = *model;
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
  PlanSetup r =
      plan_setup(line, train, plan, {ds_m, dv_kmh, "traction", "hold", threads}, frontier_span_s);
  recovery::MonteCarloRunInfo info;
  // The program names a plan file by its file name in the run's config.
  info.plan_name = r.file.empty() ? r.name : std::filesystem::path(r.file).filename().string();
  info.days_total = static_cast<std::uint64_t>(days);
  info.frontier_span_s = frontier_span_s;
  info.ds_m = ds_m;
  info.dv_kmh = dv_kmh;
  info.line_checksum = line.line.checksum();
  info.train_checksum = data::train_checksum(train.train);
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
    const recovery::MonteCarloDays result = recovery::simulate_days(
        mc, runs, 0, static_cast<std::uint64_t>(days), threads, info,
        [&](int done, int total) { check("day", done, total); }, wall0);
    out.statistics = result.summary.statistics;
    out.report = recovery::run_json(result.run, "");
    for (const auto& d : result.run.days) {
      out.traction_kJ.push_back(d.traction_kJ);
      out.substation_kJ.push_back(d.substation_kJ);
    }
    out.summary = summary_of(result.summary);
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
  py::class_<PyPlan>(delay, "Plan",
                     "A timetable plan: the stations in the order of travel and, per train in "
                     "departure order, its arrival and departure clock times (s) at each.")
      .def(py::init(&plan_from_arrays), py::arg("stations"), py::arg("arrival_s"),
           py::arg("departure_s"), py::kw_only(), py::arg("name") = "plan",
           "stations: names in the order of travel; arrival_s, departure_s: arrays of shape "
           "(trains, stations) in s (the first station's arrival equals its departure, the "
           "last's departure its arrival); name: what reports call the plan. ValueError when "
           "times fall along a train or trains are out of departure order.")
      .def_static(
          "from_csv",
          [](const py::object& path) {
            PyPlan p;
            p.file = fspath(path);
            p.name = p.file;
            p.plan = recovery::read_plan_csv(p.file);
            return p;
          },
          py::arg("path"),
          "The plan of a timetable CSV as `ecorail timetable evaluate|optimise --csv` and "
          "`montecarlo --adjust --adjusted-csv` write it (ValueError naming file, row and "
          "field).")
      .def_readonly("name", &PyPlan::name)
      .def_property_readonly("stations", [](const PyPlan& p) { return p.plan.stations; })
      .def_property_readonly("trains",
                             [](const PyPlan& p) { return static_cast<int>(p.plan.trains.size()); })
      .def_property_readonly(
          "arrival_s",
          [](const PyPlan& p) { return stop_times(p.plan, &recovery::TrainStops::arrival_s); },
          "Arrival clock times, s (float64, shape (trains, stations)).")
      .def_property_readonly(
          "departure_s",
          [](const PyPlan& p) { return stop_times(p.plan, &recovery::TrainStops::departure_s); },
          "Departure clock times, s (float64, shape (trains, stations)).");
  py::class_<PyRecovery>(delay, "Recovery",
                         "A late departure recovered: back on time at the earliest station, then "
                         "the least traction energy (kJ) over the recovery sections, beside the "
                         "seed paper's rule.")
      .def_readonly("summary", &PyRecovery::summary)
      .def(
          "to_dict", [](const PyRecovery& r) { return to_python(r.report); },
          "The document `ecorail delay --json` writes for the same plan and arguments.")
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
          "sections", [](const PyRecovery& r) { return to_python(r.report.at("sections")); },
          "One dict per recovery section, as the JSON's \"sections\": times in s, energies in kJ.");
  delay.def(
      "recover", &recover_py, py::arg("line"), py::arg("train"), py::kw_only(),
      py::arg("train_number"), py::arg("station"), py::arg("delay_s"), py::arg("plan") = py::none(),
      py::arg("min_dwell_s") = 30.0, py::arg("followers") = 5, py::arg("frontier_span_s") = 60.0,
      py::arg("ds_m") = 5.0, py::arg("dv_kmh") = 0.2, py::arg("threads") = 0,
      py::arg("cache") = true, py::arg("cache_dir") = py::none(),
      "Train train_number (1-based) of the plan leaves station delay_s seconds late, as "
      "`ecorail delay`: plan None (the 2.1 reference plan, --reference), a timetable CSV path "
      "(--plan) or an ecorail.delay.Plan. Back on time at the earliest station "
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
          "The document `ecorail montecarlo --json` writes for the same plan and arguments.")
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
        py::arg("plan") = py::none(), py::arg("days") = 100, py::arg("seed") = 1,
        py::arg("recovery") = "exact", py::arg("followers") = "driven",
        py::arg("tail") = "exponential:30", py::arg("early_s") = 10.0, py::arg("run_early_s") = 0.0,
        py::arg("min_dwell_s") = 30.0, py::arg("takeover_s") = 120.0, py::arg("punctual_s") = 10.0,
        py::arg("separation_s") = -1.0, py::arg("knot_step_s") = 1.0, py::arg("step_s") = 0.1,
        py::arg("frontier_span_s") = 60.0, py::arg("ds_m") = 5.0, py::arg("dv_kmh") = 0.2,
        py::arg("threads") = 0, py::arg("cache") = true, py::arg("cache_dir") = py::none(),
        py::arg("progress") = py::none(),
        "Whole service days of the plan under random delays, as `ecorail montecarlo`: plan "
        "None (the 2.1 reference plan), a timetable CSV path or an ecorail.delay.Plan; days from "
        "seed (counter-based draws; the same bytes for any "
        "threads), recovery 'exact', 'exact-punctual' or 'rule', followers 'driven' (as "
        "`delay` drives them) or 'shortcut' (the fast mode), delay tail e.g. "
        "'exponential:30'; times in s. cache: the program's frontier and section-run cache "
        "(cache_dir, or its default directory when None), shared with `ecorail montecarlo`.");
}

}  // namespace ecorail::python
