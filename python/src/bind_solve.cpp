// ecorail.solve (a section, or a journey over several stops), ecorail.min_time,
// ecorail.frontier and ecorail.journey (TTOBench timing points): the library's solvers with
// the program's defaults, results as ecorail.Run / ecorail.Frontier whose to_dict() is the
// document `ecorail ... --json` writes (output/solve_reports.hpp builds both).
#include <algorithm>
#include <cmath>

#include "data/csv_reader.hpp"
#include "data/input_error.hpp"
#include "data/route_builder.hpp"
#include "data/ttobench_journey.hpp"
#include "dp/frontier.hpp"
#include "dp/journey.hpp"
#include "dp/journey_plan.hpp"
#include "dp/section_solve.hpp"
#include "dp/text_format.hpp"
#include "dp/threads.hpp"
#include "dp/timing_journey.hpp"
#include "output/run_json.hpp"
#include "physics/motion.hpp"
#include "physics/speed_envelope.hpp"
#include "physics/trip.hpp"
#include "physics/units.hpp"
#include "python/src/common.hpp"

namespace ecorail::python {

namespace {

// A run: a section, a journey, a journey with timing points or a flat-out run.
struct PyRun {
  std::string kind;
  PySummary summary;
  nlohmann::json report;
  Arrays arrays;
  double number(const char* key) const {
    const auto it = report.find(key);
    return it != report.end() && it->is_number() ? it->get<double>() : NAN;
  }
};

struct PyFrontier {
  nlohmann::json report;
  dp::Frontier frontier;
};

// The stops of the run from `from` to `to`: every station between them except those passed.
std::vector<std::string> run_stops(const data::Line& line, const std::string& from,
                                   const std::string& to,
                                   const std::vector<std::string>& pass_through) {
  const std::vector<std::string> all = data::stops_between(line, from, to);
  for (const auto& name : pass_through) {
    if (std::find(all.begin() + 1, all.end() - 1, name) == all.end() - 1) {
      std::string list;
      for (std::size_t i = 1; i + 1 < all.size(); ++i) list += (list.empty() ? "" : ", ") + all[i];
      bad_argument("pass_through",
                   "a station between from_ and to (" + (list.empty() ? "none here" : list) + ")",
                   "'" + name + "'");
    }
  }
  std::vector<std::string> stops;
  for (std::size_t i = 0; i < all.size(); ++i) {
    const bool passed =
        i > 0 && i + 1 < all.size() &&
        std::find(pass_through.begin(), pass_through.end(), all[i]) != pass_through.end();
    if (!passed) stops.push_back(all[i]);
  }
  return stops;
}

double dwell_seconds(const py::handle& value, const std::string& label) {
  double v = NAN;
  try {
    v = py::cast<double>(value);
  } catch (const py::cast_error&) {
  }
  if (!std::isfinite(v) || v < 0.0) {
    bad_argument("dwell", "a dwell in seconds >= 0", label + " = " + std::string(py::repr(value)));
  }
  return v;
}

// dwell: None, seconds for every stop, {station: seconds} (the key "*" for every stop not
// named), or the program's strings ["A7=45", "30"]. Also the provenance's "dwells", written as
// the program writes them.
dp::DwellSpec dwell_spec(const py::object& dwell, std::vector<std::string>* as_text) {
  dp::DwellSpec spec;
  if (dwell.is_none()) return spec;
  if (py::isinstance<py::dict>(dwell)) {
    for (const auto& [key, value] : py::cast<py::dict>(dwell)) {
      const std::string name = py::str(key);
      const double s = dwell_seconds(value, name);
      if (name == "*") {
        spec.every_stop_s = s;
        as_text->push_back(data::format_number(s));
      } else {
        spec.by_stop_s.emplace_back(name, s);
        as_text->push_back(name + "=" + data::format_number(s));
      }
    }
    return spec;
  }
  if (py::isinstance<py::list>(dwell) || py::isinstance<py::tuple>(dwell)) {
    for (const auto& item : dwell) {
      const std::string text = py::str(item);
      as_text->push_back(text);
      const auto eq = text.find('=');
      const std::string number = eq == std::string::npos ? text : text.substr(eq + 1);
      char* end = nullptr;
      const double v = std::strtod(number.c_str(), &end);
      if (number.empty() || *end != '\0' || !std::isfinite(v) || v < 0.0) {
        bad_argument("dwell", "a dwell in seconds >= 0 (e.g. '30' or 'A7=45')", "'" + text + "'");
      }
      if (eq == std::string::npos) {
        spec.every_stop_s = v;
      } else {
        spec.by_stop_s.emplace_back(text.substr(0, eq), v);
      }
    }
    return spec;
  }
  const double s = dwell_seconds(dwell, "every stop");
  spec.every_stop_s = s;
  as_text->push_back(data::format_number(s));
  return spec;
}

void check_time(double time_s) {
  if (!(time_s > 0.0) || !std::isfinite(time_s)) {
    bad_argument("time_s", "a running time in seconds > 0", data::format_number(time_s));
  }
}

py::object run_object(PyRun run) {
  const bool usable = run.summary.is_solution_usable();
  const std::string brief = run.summary.brief_report;
  py::object obj = py::cast(std::move(run));
  if (!usable) raise_solve_error("the run misses its stop or its running time: " + brief, obj);
  return obj;
}

py::object solve_section_py(const PyLine& line, const PyTrain& train, const std::string& from,
                            const std::string& to, double time_s, const EngineArgs& engine,
                            const dp::MinRegimeOptions& min_regime, const py::object& progress) {
  dp::SectionSolveOptions options;
  options.engine = engine_options(engine, train);
  options.min_regime = min_regime;
  require_valid(options);
  const physics::Route route = data::build_route(line.line, from, to, train.train);
  Interruptible guard(progress);
  options.search.progress = guard.callback();
  dp::SectionSolution solution =
      guard.run([&] { return dp::solve_section(train.train, route, time_s, options); });
  const auto& s = solution.summary;
  PyRun run;
  run.kind = "section";
  run.summary = summary_of(s, s.warnings);
  const std::string cap_note = output::speed_cap_note(line.line, {s.from, s.to}, train.train);
  run.report = output::section_report_json(
      solution, train.train, cap_note,
      output::run_provenance_json(
          line.line, train.train,
          run_inputs(line, train, from, to, engine.objective, engine.ds_m, engine.dv_kmh),
          {{"time_s", time_s},
           {"min_regime_m", min_regime.min_length_m},
           {"min_regime_s", min_regime.min_duration_s}}));
  const physics::Trip trip({{&route, &solution.run.sim, 0.0}}, 0.0, train.train.regen_efficiency);
  run.arrays = per_second_arrays(output::trip_timeline(trip));
  return run_object(std::move(run));
}

py::object solve_journey_py(const PyLine& line, const PyTrain& train,
                            const std::vector<std::string>& stops, double time_s,
                            const py::object& dwell, const std::string& split,
                            const std::string& marginals, const EngineArgs& engine,
                            const dp::MinRegimeOptions& min_regime, const py::object& progress) {
  std::vector<std::string> dwell_text;
  const dp::DwellSpec spec = dwell_spec(dwell, &dwell_text);
  const std::vector<double> dwells = dp::resolve_dwells(spec, stops);
  dp::JourneyOptions options;
  options.engine = engine_options(engine, train);
  const auto split_kind = dp::split_from_name(split);
  if (!split_kind) bad_argument("split", "'optimal' or 'proportional'", "'" + split + "'");
  options.split = *split_kind;
  if (marginals != "on" && marginals != "off" && marginals != "auto") {
    bad_argument("marginals", "'on', 'off' or 'auto'", "'" + marginals + "'");
  }
  options.measure_marginals = marginals == "on" || (marginals == "auto" && stops.size() - 1 <= 4);
  options.min_regime = min_regime;
  require_valid(options);
  const std::vector<physics::Route> routes = data::build_routes(line.line, stops, train.train);
  Interruptible guard(progress);
  options.search.progress = guard.callback();
  dp::JourneySolution sol =
      guard.run([&] { return dp::solve_journey(train.train, routes, dwells, time_s, options); });
  PyRun run;
  run.kind = "journey";
  run.summary = summary_of(sol.summary, sol.warnings);
  const output::JourneyLabels labels{stops, split, engine.ds_m, engine.dv_kmh, sol.summary.threads};
  run.report = output::journey_report_json(
      sol, labels, train.train, output::speed_cap_note(line.line, stops, train.train), min_regime,
      output::run_provenance_json(line.line, train.train,
                                  run_inputs(line, train, stops.front(), stops.back(),
                                             engine.objective, engine.ds_m, engine.dv_kmh),
                                  {{"time_s", time_s},
                                   {"dwells", dwell_text},
                                   {"split", split},
                                   {"min_regime_m", min_regime.min_length_m},
                                   {"min_regime_s", min_regime.min_duration_s}}));
  run.arrays = per_second_arrays(output::journey_timeline(sol, routes));
  return run_object(std::move(run));
}

py::object solve_py(const PyLine& line, const PyTrain& train, const std::string& from,
                    const std::string& to, double time_s, const py::object& dwell,
                    const std::string& split, const std::vector<std::string>& pass_through,
                    double min_regime_m, double min_regime_s, const std::string& marginals,
                    double ds_m, double dv_kmh, const std::string& objective,
                    const std::string& cruise, int threads, const py::object& progress) {
  check_time(time_s);
  const EngineArgs engine{ds_m, dv_kmh, objective, cruise, threads};
  dp::MinRegimeOptions min_regime;
  min_regime.min_length_m = min_regime_m;
  min_regime.min_duration_s = min_regime_s;
  const std::vector<std::string> stops = run_stops(line.line, from, to, pass_through);
  if (stops.size() > 2) {
    return solve_journey_py(line, train, stops, time_s, dwell, split, marginals, engine, min_regime,
                            progress);
  }
  return solve_section_py(line, train, from, to, time_s, engine, min_regime, progress);
}

py::object min_time_py(const PyLine& line, const PyTrain& train, const std::string& from,
                       const std::string& to, double ds_m, double dv_kmh,
                       const std::string& objective) {
  const EngineArgs engine{ds_m, dv_kmh, objective, "hold", 0};
  require_valid(engine_options(engine, train));
  const std::vector<std::string> stops = run_stops(line.line, from, to, {});
  if (stops.size() > 2) {
    bad_argument("to", "a station next to from_ (a flat-out run is of one section)",
                 "'" + to + "', which stops at " + stops[1]);
  }
  const physics::Route route = data::build_route(line.line, from, to, train.train);
  physics::SimulationResult sim;
  {
    py::gil_scoped_release release;
    const physics::SpeedEnvelope envelope(train.train, route);
    const physics::Motion motion(train.train, route, envelope);
    sim = physics::simulate(motion, {{0.0, physics::Control::MaxTraction}}, {});
  }
  PyRun run;
  run.kind = "min-time";
  const bool arrives = dp::run_arrives(sim);
  run.summary.termination = dp::termination_of(arrives, true);
  run.summary.brief_report = dp::format_text(
      "ecorail min-time %s -> %s (%.1f m): minimum running time %.3f s, traction %.1f kJ, stop "
      "error %.3f m\n",
      route.from_name().c_str(), route.to_name().c_str(), route.length_m(), sim.running_time_s,
      units::J_to_kJ(sim.energy.traction_work_J), sim.stop_error_m);
  run.summary.full_report = run.summary.brief_report;
  run.report = output::min_time_report_json(
      route, sim, train.train,
      output::run_provenance_json(line.line, train.train,
                                  run_inputs(line, train, from, to, objective, ds_m, dv_kmh)));
  const physics::Trip trip({{&route, &sim, 0.0}}, 0.0, train.train.regen_efficiency);
  run.arrays = per_second_arrays(output::trip_timeline(trip));
  return run_object(std::move(run));
}

PyFrontier frontier_py(const PyLine& line, const PyTrain& train, const std::string& from,
                       const std::string& to, double tmin_s, double tmax_s, double step_s,
                       double ds_m, double dv_kmh, const std::string& objective,
                       const std::string& cruise, int threads, const py::object& progress) {
  if (!(step_s > 0.0)) bad_argument("step_s", "a step in s > 0", data::format_number(step_s));
  if (tmax_s > 0.0 && tmax_s < tmin_s) {
    bad_argument("tmax_s", "a time above tmin_s", data::format_number(tmax_s));
  }
  const EngineArgs engine{ds_m, dv_kmh, objective, cruise, threads};
  const dp::EngineOptions engine_opts = engine_options(engine, train);
  require_valid(engine_opts);
  const std::vector<std::string> stops = data::stops_between(line.line, from, to);
  if (stops.size() != 2) {
    bad_argument("to", "the station next to from_ (a frontier is of one section)", "'" + to + "'");
  }
  dp::FrontierOptions options;
  options.t_min_s = tmin_s;
  options.t_max_s = tmax_s;
  options.step_s = step_s;
  require_valid(options);
  const physics::Route route = data::build_route(line.line, from, to, train.train);
  Interruptible guard(progress);
  options.progress = guard.callback();
  output::LabelledFrontier lf{from, to, {}};
  try {
    lf.frontier = guard.run([&] {
      const dp::SectionEngine section(train.train, route, engine_opts);
      return dp::compute_frontier(section, options);
    });
  } catch (const dp::InfeasibleTimeError& e) {
    const bool tmin = tmin_s > 0.0 && tmin_s < e.minimum_s();
    bad_argument(tmin ? "tmin_s" : "tmax_s",
                 "at least the minimum running time of " +
                     data::format_number(std::round(e.minimum_s() * 100) / 100) + " s for " + from +
                     " -> " + to + " (flat-out run)",
                 data::format_number(tmin ? tmin_s : tmax_s) + " s");
  }
  PyFrontier f;
  f.report = output::frontier_report_json(
      {lf}, false, ds_m, dv_kmh,
      output::run_provenance_json(line.line, train.train,
                                  run_inputs(line, train, from, to, objective, ds_m, dv_kmh),
                                  {{"tmin_s", tmin_s},
                                   {"tmax_s", tmax_s},
                                   {"step_s", step_s},
                                   {"all", false},
                                   {"cache", false}}));
  f.frontier = std::move(lf.frontier);
  return f;
}

py::object journey_py(const PyLine& line, const PyTrain& train, const py::object& journey_path,
                      double ds_m, double dv_kmh, const std::string& objective,
                      const std::string& cruise, int threads, const py::object& progress) {
  const std::string path = fspath(journey_path);
  const data::TtobenchJourney journey =
      data::journey_from_ttobench(data::read_text_file(path), path);
  dp::TimingJourneyOptions options;
  const EngineArgs engine{ds_m, dv_kmh, objective, cruise, threads};
  options.engine = engine_options(engine, train);
  require_valid(options);
  // Ctrl-C (and the user's progress callable) is seen after each price evaluation.
  Interruptible guard(progress);
  options.progress = guard.callback();
  if (line.line.stations.size() < 2) {
    throw data::InputError(line.source, 0, "stops", "at least two stops");
  }
  const physics::Route track = data::build_route(line.line, line.line.stations.front().name,
                                                 line.line.stations.back().name, train.train);
  dp::TimingJourneySolution sol;
  try {
    sol = guard.run([&] {
      return dp::solve_timing_journey(train.train, track, journey.points, options, journey.id);
    });
  } catch (const dp::WindowInfeasibleError& e) {
    throw data::InputError(path, 0, "timing points.values[" + std::to_string(e.point()) + "]",
                           std::string("a window a run can meet: ") + e.what());
  }
  PyRun run;
  run.kind = "timing journey";
  const auto& s = sol.summary;
  run.summary = summary_of(s, s.warnings);
  run.report = output::timing_journey_report_json(
      sol, journey.id, ds_m, dv_kmh,
      output::run_provenance_json(line.line, train.train,
                                  run_inputs(line, train, "", "", objective, ds_m, dv_kmh),
                                  {{"journey", path}}));
  run.arrays = per_second_arrays(output::journey_timeline(sol.journey, sol.routes));
  return run_object(std::move(run));
}

constexpr const char* kEngineDoc =
    "\n  ds_m, dv_kmh: grid steps in m and km/h (default 5 m, 0.2 km/h)"
    "\n  objective: 'traction' (traction energy) or 'net' (also credit regenerated energy)"
    "\n  cruise: 'hold' (a long cruise as one polished speed hold) or 'grid'"
    "\n  threads: OpenMP threads (0: all cores; results do not depend on it)";

}  // namespace

void bind_solve(py::module_& m) {
  py::class_<PyRun>(m, "Run",
                    "A re-simulated run (5 cm RK4): a section, a journey, a journey with timing "
                    "points or a flat-out run. Figures in kJ, s, m; per-second arrays as in the "
                    "program's --csv (one row per whole second plus the final instant).")
      .def_readonly("kind", &PyRun::kind, "'section', 'journey', 'timing journey' or 'min-time'.")
      .def_readonly("summary", &PyRun::summary)
      .def(
          "to_dict", [](const PyRun& r) { return to_python(r.report); },
          "The report as a dict: the document `ecorail ... --json` writes for the same inputs "
          "(keys: docs/outputs.md).")
      .def_property_readonly(
          "traction_energy_kJ", [](const PyRun& r) { return r.number("traction_energy_kJ"); },
          "Traction work at the wheel in kJ.")
      .def_property_readonly("braking_energy_kJ",
                             [](const PyRun& r) { return r.number("braking_energy_kJ"); })
      .def_property_readonly(
          "regen_energy_kJ", [](const PyRun& r) { return r.number("regen_energy_kJ"); },
          "Regenerated energy in kJ.")
      .def_property_readonly("net_energy_kJ",
                             [](const PyRun& r) { return r.number("net_energy_kJ"); })
      .def_property_readonly(
          "running_time_s", [](const PyRun& r) { return r.number("running_time_s"); },
          "Running time in s (dwells excluded).")
      .def_property_readonly("stop_error_m",
                             [](const PyRun& r) { return r.number("stop_error_m"); })
      .def_property_readonly(
          "lambda_kJ_per_s", [](const PyRun& r) { return r.number("lambda"); },
          "The time price in kJ/s (NaN where there is none).")
      .def_property_readonly(
          "time_s", [](const PyRun& r) { return to_numpy(r.arrays.time_s); },
          "Time since departure in s (float64).")
      .def_property_readonly(
          "position_m", [](const PyRun& r) { return to_numpy(r.arrays.position_m); },
          "Distance from the start in m (float64).")
      .def_property_readonly(
          "speed_ms", [](const PyRun& r) { return to_numpy(r.arrays.speed_ms); },
          "Speed in m/s (float64).")
      .def_property_readonly("accel_m_s2",
                             [](const PyRun& r) { return to_numpy(r.arrays.accel_m_s2); })
      .def_property_readonly(
          "traction_N", [](const PyRun& r) { return to_numpy(r.arrays.traction_N); },
          "Traction force in N (float64, >= 0).")
      .def_property_readonly(
          "braking_N", [](const PyRun& r) { return to_numpy(r.arrays.braking_N); },
          "Braking force in N (float64, >= 0).")
      .def_property_readonly(
          "power_W", [](const PyRun& r) { return to_numpy(r.arrays.power_W); },
          "Traction power in W (traction force times speed; float64).")
      .def_property_readonly("km_post_m",
                             [](const PyRun& r) { return to_numpy(r.arrays.km_post_m); })
      .def_property_readonly("gradient_permille",
                             [](const PyRun& r) { return to_numpy(r.arrays.gradient_permille); })
      .def_property_readonly("speed_limit_ms",
                             [](const PyRun& r) { return to_numpy(r.arrays.speed_limit_ms); })
      .def_property_readonly(
          "section", [](const PyRun& r) { return to_numpy(r.arrays.section); },
          "Section index of each row (int32).")
      .def_property_readonly(
          "regime", [](const PyRun& r) { return to_numpy(r.arrays.regime); },
          "Regime of each row: full_traction, partial_traction, coast, "
          "partial_braking, full_braking, dwell (str array).")
      .def("__repr__", [](const PyRun& r) {
        return "<ecorail.Run " + r.kind + ": " + r.summary.brief_report + ">";
      });

  py::class_<PyFrontier>(m, "Frontier",
                         "The energy-time frontier of one section: one re-simulated optimum per "
                         "running time (arrays, float64).")
      .def(
          "to_dict", [](const PyFrontier& f) { return to_python(f.report); },
          "The document `ecorail frontier --no-cache --json` writes for the same inputs.")
      .def_property_readonly(
          "min_time_s", [](const PyFrontier& f) { return f.frontier.min_time_s; },
          "The flat-out running time in s.")
      .def_property_readonly("monotone", [](const PyFrontier& f) { return f.frontier.monotone; })
      .def_property_readonly("convex", [](const PyFrontier& f) { return f.frontier.convex; })
      .def_property_readonly(
          "target_time_s",
          [](const PyFrontier& f) {
            std::vector<double> v;
            for (const auto& p : f.frontier.points) v.push_back(p.target_time_s);
            return to_numpy(v);
          },
          "Running time asked for, s.")
      .def_property_readonly(
          "running_time_s",
          [](const PyFrontier& f) {
            std::vector<double> v;
            for (const auto& p : f.frontier.points) v.push_back(p.running_time_s);
            return to_numpy(v);
          },
          "Re-simulated running time, s.")
      .def_property_readonly(
          "traction_energy_kJ",
          [](const PyFrontier& f) {
            std::vector<double> v;
            for (const auto& p : f.frontier.points) v.push_back(units::J_to_kJ(p.traction_work_J));
            return to_numpy(v);
          },
          "Traction work in kJ.")
      .def_property_readonly("regen_energy_kJ",
                             [](const PyFrontier& f) {
                               std::vector<double> v;
                               for (const auto& p : f.frontier.points)
                                 v.push_back(units::J_to_kJ(p.regen_J));
                               return to_numpy(v);
                             })
      .def_property_readonly(
          "cost_kJ",
          [](const PyFrontier& f) {
            std::vector<double> v;
            for (const auto& p : f.frontier.points) v.push_back(units::J_to_kJ(p.cost_J));
            return to_numpy(v);
          },
          "Energy by the objective (traction input or net), kJ.")
      .def_property_readonly(
          "lambda_kJ_per_s",
          [](const PyFrontier& f) {
            std::vector<double> v;
            for (const auto& p : f.frontier.points) v.push_back(p.lambda_J_per_s / 1000.0);
            return to_numpy(v);
          },
          "Time price, kJ/s (inf at the flat-out point).");

  m.def("solve", &solve_py, py::arg("line"), py::arg("train"), py::kw_only(), py::arg("from_"),
        py::arg("to"), py::arg("time_s"), py::arg("dwell") = py::none(),
        py::arg("split") = "optimal", py::arg("pass_through") = std::vector<std::string>{},
        py::arg("min_regime_m") = 0.0, py::arg("min_regime_s") = 0.0, py::arg("marginals") = "auto",
        py::arg("ds_m") = 5.0, py::arg("dv_kmh") = 0.2, py::arg("objective") = "traction",
        py::arg("cruise") = "hold", py::arg("threads") = 0, py::arg("progress") = py::none(),
        (std::string(
             "Least-energy run from from_ to to, as `ecorail solve`; every figure re-simulated.\n"
             "\n  time_s: running time in s (dwells excluded)"
             "\n  dwell: with stops between from_ and to (a journey): seconds at every stop, "
             "{'A7': 45} by station ('*': the rest), or ['A7=45', '30']"
             "\n  split: 'optimal' (one time price for all sections) or 'proportional'"
             "\n  pass_through: stations passed without stopping"
             "\n  min_regime_m, min_regime_s: merge control phases shorter than this (m, s)"
             "\n  marginals: 'on', 'off', 'auto' (journeys of up to 4 sections)") +
         kEngineDoc +
         "\n  progress: progress(stage, done, total), called between stages; may raise to stop"
         "\n\nReturns an ecorail.Run (kJ, s, m; per-second numpy arrays). A run that misses its "
         "stop or time raises ecorail.SolveError; bad input raises ValueError naming the "
         "argument; Ctrl-C raises KeyboardInterrupt.")
            .c_str());
  m.def("min_time", &min_time_py, py::arg("line"), py::arg("train"), py::kw_only(),
        py::arg("from_"), py::arg("to"), py::arg("ds_m") = 5.0, py::arg("dv_kmh") = 0.2,
        py::arg("objective") = "traction",
        "The flat-out run of one section (full traction, held on the limits, braking for the "
        "stop), as `ecorail min-time`: its running_time_s is the lower bound of solve's time_s. "
        "ds_m, dv_kmh and objective only label the report.");
  m.def("frontier", &frontier_py, py::arg("line"), py::arg("train"), py::kw_only(),
        py::arg("from_"), py::arg("to"), py::arg("tmin_s") = 0.0, py::arg("tmax_s") = 0.0,
        py::arg("step_s") = 1.0, py::arg("ds_m") = 5.0, py::arg("dv_kmh") = 0.2,
        py::arg("objective") = "traction", py::arg("cruise") = "hold", py::arg("threads") = 0,
        py::arg("progress") = py::none(),
        (std::string("Energy-time frontier of one section, as `ecorail frontier --no-cache`.\n"
                     "\n  tmin_s: first running time in s (0: the flat-out time)"
                     "\n  tmax_s: last running time in s (0: flat-out + 60 s)"
                     "\n  step_s: time step in s") +
         kEngineDoc + "\n  progress: progress(stage, done, total) after each point; may raise")
            .c_str());
  m.def("journey", &journey_py, py::arg("line"), py::arg("train"), py::arg("journey"),
        py::kw_only(), py::arg("ds_m") = 5.0, py::arg("dv_kmh") = 0.2,
        py::arg("objective") = "traction", py::arg("cruise") = "hold", py::arg("threads") = 0,
        py::arg("progress") = py::none(),
        (std::string("A TTOBench journey with timing points (path to its JSON) on line's track, "
                     "as `ecorail solve --journey`: least energy subject to every time and speed "
                     "window. Windows no run can meet raise ValueError naming the window. "
                     "progress(stage, done, total) is called after each price evaluation (Ctrl-C "
                     "stops the solve there). ") +
         kEngineDoc)
            .c_str());
}

}  // namespace ecorail::python
