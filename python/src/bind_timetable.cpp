// ecorail.timetable.evaluate / optimise: fleet timetables that use regenerated braking energy
// (question 2.1), a thin wrapper over the library the program's `timetable` command calls:
// timetable::optimal_split_pattern (the pattern of every train), timetable::FleetModels
// (evaluate), timetable::optimise_headways (optimise), PowerBalance::trace (per-bin power), and
// output::fleet_energy_json / add_network_json for to_dict(). Pattern optimisation (--optimise
// pattern) and the separation check are the program's for now (docs/python.md).
#include <cmath>

#include "data/route_builder.hpp"
#include "dp/section_library.hpp"
#include "output/fleet_outputs.hpp"
#include "power/supply_loader.hpp"
#include "python/src/common.hpp"
#include "timetable/fleet_models.hpp"
#include "timetable/fleet_pattern.hpp"
#include "timetable/headway_optimiser.hpp"
#include "timetable/network_evaluation.hpp"
#include "timetable/power_balance.hpp"

namespace ecorail::python {

namespace {

using Range = std::pair<double, double>;

struct FleetArgs {
  std::string model = "power-flow", overlap = "ahead";
  double step_s = NAN;
  std::vector<double> sections_at_m;
  std::string power_supply;  // path; empty: none
  int trains = 100, span_s = 63900;
  Range headway_s{120, 660};
  double trip_time_s = 2086.0, dwell_s = 30.0;
  Range dwell_range_s{30, 45};
  std::vector<Range> peaks;
  Range peak_headway_s{120, 150}, offpeak_headway_s{300, 660};
  EngineArgs engine;
};

int whole(double v, const std::string& field) {
  if (v != std::floor(v) || std::fabs(v) > 1e9) {
    bad_argument(field, "whole seconds", std::to_string(v));
  }
  return static_cast<int>(v);
}

struct PyFleet {
  std::string stage;  // "evaluate" or "optimise"
  nlohmann::json report;
  timetable::FleetEvaluation evaluation;
  PySummary summary;
  double trace_start_s = 0.0, trace_step_s = 0.0;
  std::vector<double> traction_W, regen_W, used_W;
};

// The problem, the pattern every train drives and its models, as the program sets them up.
struct FleetSetup {
  timetable::FleetProblem problem;
  timetable::EnergyModelOptions model;
  std::vector<std::string> stops;
  std::unique_ptr<dp::SectionLibrary> library;
  timetable::PatternTrip pattern;
  std::unique_ptr<timetable::FleetModels> models;
};

timetable::FleetProblem fleet_problem(const FleetArgs& a) {
  timetable::FleetProblem p;
  p.trains = a.trains;
  p.span_s = a.span_s;
  p.headway_min_s = whole(a.headway_s.first, "headway_s");
  p.headway_max_s = whole(a.headway_s.second, "headway_s");
  p.trip_time_s = a.trip_time_s;
  p.dwell_min_s = a.dwell_range_s.first;
  p.dwell_max_s = a.dwell_range_s.second;
  for (const auto& [from, to] : a.peaks) {
    p.peak_windows.push_back({whole(from, "peaks"), whole(to, "peaks")});
  }
  if (p.windowed()) {
    p.peak_headway_min_s = whole(a.peak_headway_s.first, "peak_headway_s");
    p.peak_headway_max_s = whole(a.peak_headway_s.second, "peak_headway_s");
    p.headway_min_s = whole(a.offpeak_headway_s.first, "offpeak_headway_s");
    p.headway_max_s = whole(a.offpeak_headway_s.second, "offpeak_headway_s");
  }
  require_valid(p);
  if (!(a.dwell_s >= p.dwell_min_s && a.dwell_s <= p.dwell_max_s)) {
    bad_argument("dwell_s", "a dwell within dwell_range_s", std::to_string(a.dwell_s));
  }
  return p;
}

// The line's sections, the energy model and the pattern every train drives: built once, then
// any number of fleet problems and timetables on it (ecorail.timetable.Fleet).
FleetSetup setup_line(const PyLine& line, const PyTrain& train, const FleetArgs& a) {
  FleetSetup s;
  const auto model = timetable::model_from_name(a.model);
  if (!model)
    bad_argument("model", "'power-flow', 'overlap', 'sections' or 'network'", "'" + a.model + "'");
  s.model.model = *model;
  const auto variant = timetable::overlap_variant_from_name(a.overlap);
  if (!variant) bad_argument("overlap", "'ahead' or 'either'", "'" + a.overlap + "'");
  s.model.overlap = *variant;
  s.model.time_step_s =
      std::isnan(a.step_s)
          ? (*model == timetable::EnergyModel::Network ? timetable::kNetworkTimeStep_s : 0.01)
          : a.step_s;
  s.model.section_boundaries_m = a.sections_at_m;
  if (*model == timetable::EnergyModel::Network) {
    if (a.power_supply.empty()) {
      bad_argument("power_supply", "a power-supply file (TOML) for model='network'", "None");
    }
    s.model.power_supply =
        std::make_shared<const power::PowerSupply>(power::load_power_supply(a.power_supply));
  } else if (!a.power_supply.empty()) {
    bad_argument("power_supply", "model='network' (the other models have no supply network)",
                 "a file");
  }
  if (*model == timetable::EnergyModel::Sections && s.model.section_boundaries_m.empty()) {
    bad_argument("sections_at_m", "at least one supply-section boundary (m) for model='sections'",
                 "none");
  }
  if (train.train.has_efficiency_maps()) {
    bad_argument("train", "a train with constant efficiencies for the fleet models",
                 "'" + train.train.name + "'");
  }
  s.model.traction_efficiency = train.train.traction_efficiency;
  require_valid(s.model);
  if (!(a.trip_time_s > 0.0))
    bad_argument("trip_time_s", "a trip time in s > 0", std::to_string(a.trip_time_s));
  if (!(a.dwell_s >= 0.0)) bad_argument("dwell_s", "a dwell in s >= 0", std::to_string(a.dwell_s));
  s.stops = data::stops_between(line.line, line.line.stations.front().name,
                                line.line.stations.back().name);
  dp::SectionLibraryOptions lib_options;
  lib_options.engine = engine_options(a.engine, train);
  require_valid(lib_options.engine);
  s.library = std::make_unique<dp::SectionLibrary>(
      train.train, data::build_routes(line.line, s.stops, train.train), lib_options);
  const std::vector<double> dwells(s.stops.size() - 2, a.dwell_s);
  dp::JourneyOptions journey;
  journey.engine = lib_options.engine;
  journey.measure_marginals = false;
  try {
    s.pattern = timetable::optimal_split_pattern(*s.library, dwells, a.trip_time_s, journey);
  } catch (const dp::InfeasibleTimeError& e) {
    bad_argument("trip_time_s",
                 "a trip time that leaves at least the flat-out running time of " +
                     std::to_string(e.minimum_s()) + " s after the dwells",
                 std::to_string(a.trip_time_s));
  }
  return s;
}

// The fleet problem of a and the models on it.
void set_problem(FleetSetup& s, const FleetArgs& a) {
  s.problem = fleet_problem(a);
  s.models = std::make_unique<timetable::FleetModels>(s.pattern.trip, s.problem, s.model);
}

// The report as the program writes it (without the separation check) and the power per bin.
void finish(PyFleet& out, const FleetSetup& s, const timetable::FleetEvaluation& ev) {
  out.evaluation = ev;
  out.report = output::fleet_energy_json(ev, s.problem);
  out.report["pattern"] = {{"dwells_s", s.pattern.pattern.dwells_s},
                           {"running_times_s", s.pattern.pattern.running_times_s},
                           {"trip_time_s", s.pattern.pattern.trip_time_s()}};
  out.report["stations"] = s.stops;
  if (ev.network) output::add_network_json(out.report, *ev.network);
  if (ev.model == timetable::EnergyModel::PowerFlow ||
      ev.model == timetable::EnergyModel::Sections) {
    auto balance = s.models->make_balance();
    balance->place_all(ev.departures_s);
    const double end_s =
        ev.departures_s.empty() ? 0.0 : ev.departures_s.back() + s.pattern.pattern.trip_time_s();
    const auto trace = balance->trace(0.0, end_s);
    out.trace_start_s = trace.start_s;
    out.trace_step_s = trace.step_s;
    out.traction_W = trace.traction_W;
    out.regen_W = trace.regen_W;
    out.used_W = trace.used_W;
  }
}

std::vector<int> given_departures(const FleetSetup& s, const py::object& departures_s,
                                  const py::object& headways_s) {
  if (!departures_s.is_none() && !headways_s.is_none()) {
    bad_argument("departures_s", "either departures_s or headways_s, not both", "both");
  }
  std::vector<int> t;
  if (!departures_s.is_none()) {
    for (const auto& v : departures_s) t.push_back(whole(py::cast<double>(v), "departures_s"));
  } else if (!headways_s.is_none()) {
    std::vector<int> h;
    for (const auto& v : headways_s) h.push_back(whole(py::cast<double>(v), "headways_s"));
    t = timetable::departures_from_headways(h);
  } else {
    t = timetable::departures_from_headways(timetable::uniform_headways(s.problem));
  }
  const std::string why = timetable::departures_problem(s.problem, t);
  if (!why.empty())
    bad_argument(departures_s.is_none() ? "headways_s" : "departures_s",
                 "departures that keep the problem", why);
  return t;
}

// ecorail.timetable.Fleet: the line's sections and the pattern, built once for many timetables.
struct PyFleetLine {
  FleetArgs args;
  std::shared_ptr<FleetSetup> setup;
};

PyFleetLine make_fleet(const PyLine& line, const PyTrain& train, const FleetArgs& a) {
  PyFleetLine f{a, std::make_shared<FleetSetup>()};
  py::gil_scoped_release release;  // builds the line's sections and solves the pattern
  *f.setup = setup_line(line, train, a);
  return f;
}

// The fleet's arguments with the problem's own (trains, span, headways, peaks).
FleetArgs with_problem(const PyFleetLine& f, int trains, int span_s, Range headway_s,
                       Range dwell_range_s, std::vector<Range> peaks, Range peak_headway_s,
                       Range offpeak_headway_s) {
  FleetArgs a = f.args;
  a.trains = trains;
  a.span_s = span_s;
  a.headway_s = headway_s;
  a.dwell_range_s = dwell_range_s;
  a.peaks = std::move(peaks);
  a.peak_headway_s = peak_headway_s;
  a.offpeak_headway_s = offpeak_headway_s;
  return a;
}

PyFleet evaluate_py(const PyFleetLine& f, const FleetArgs& a, const py::object& departures_s,
                    const py::object& headways_s) {
  FleetSetup& s = *f.setup;
  {
    py::gil_scoped_release release;
    set_problem(s, a);
  }
  const std::vector<int> departures = given_departures(s, departures_s, headways_s);
  PyFleet out;
  out.stage = "evaluate";
  timetable::FleetEvaluation ev;
  {
    py::gil_scoped_release release;
    ev = s.models->evaluate(departures);
  }
  out.summary.termination = dp::Termination::CONVERGENCE;
  finish(out, s, ev);
  return out;
}

PyFleet optimise_py(const PyFleetLine& f, const FleetArgs& a, std::uint64_t seed,
                    double time_limit_s, int restarts, long moves, double anneal_step_s,
                    const py::object& progress) {
  FleetSetup& s = *f.setup;
  {
    py::gil_scoped_release release;
    set_problem(s, a);
  }
  timetable::HeadwayOptimiserOptions o;
  o.seed = seed;
  o.time_limit_s = time_limit_s;
  o.restarts = restarts;
  o.moves_per_run = moves;
  o.anneal_step_s = anneal_step_s;
  o.threads = a.engine.threads;
  require_valid(o);
  Interruptible guard(progress);
  const dp::ProgressFn check = guard.callback();
  o.progress = [&check](const timetable::OptimiserProgress& p) { check(p.stage.c_str(), 0, 0); };
  const timetable::HeadwayOptimiserResult result =
      guard.run([&] { return timetable::optimise_headways(*s.models, o); });
  const auto& sm = result.summary;
  PyFleet out;
  out.stage = "optimise";
  out.summary = {sm.termination, sm.BriefReport(), sm.FullReport(), {}};
  finish(out, s, result.evaluation);
  if (std::isfinite(sm.bound_substation_J)) {
    out.report["bound_substation_kJ"] = sm.bound_substation_J / 1e3;
    out.report["gap_fraction_of_substation"] = sm.gap_fraction;
  } else if (std::isfinite(sm.bound_used_regen_J)) {
    out.report["bound_used_regen_kJ"] = sm.bound_used_regen_J / 1e3;
    out.report["gap_fraction_of_substation"] = sm.gap_fraction;
    if (sm.pair_sum_J > 0.0) out.report["pair_sum_of_result_kJ"] = sm.pair_sum_J / 1e3;
  }
  out.report["summary"] = {{"termination", std::string(dp::termination_name(sm.termination))},
                           {"method", sm.method},
                           {"exact", sm.exact},
                           {"seed", seed},
                           {"moves", sm.moves},
                           {"wall_s", sm.wall_s},
                           {"brief_report", sm.BriefReport()}};
  if (!sm.IsSolutionUsable()) {
    raise_solve_error("the optimiser failed: " + sm.message, py::cast(out));
  }
  return out;
}

std::vector<double> per_train(const timetable::FleetEvaluation& ev,
                              double (*f)(const timetable::FleetEnergy&)) {
  std::vector<double> v;
  for (const auto& e : ev.per_train) v.push_back(f(e) / 1e3);
  return v;
}

void add_fleet_args(FleetArgs& a, const std::string& model, const std::string& overlap,
                    double step_s, std::vector<double> sections_at_m, py::object power_supply,
                    int trains, int span_s, Range headway_s, double trip_time_s, double dwell_s,
                    Range dwell_range_s, std::vector<Range> peaks, Range peak_headway_s,
                    Range offpeak_headway_s, double ds_m, double dv_kmh, int threads) {
  a.model = model;
  a.overlap = overlap;
  a.step_s = step_s;
  a.sections_at_m = std::move(sections_at_m);
  if (!power_supply.is_none()) {
    a.power_supply = py::str(py::module_::import("os").attr("fspath")(power_supply));
  }
  a.trains = trains;
  a.span_s = span_s;
  a.headway_s = headway_s;
  a.trip_time_s = trip_time_s;
  a.dwell_s = dwell_s;
  a.dwell_range_s = dwell_range_s;
  a.peaks = std::move(peaks);
  a.peak_headway_s = peak_headway_s;
  a.offpeak_headway_s = offpeak_headway_s;
  a.engine = {ds_m, dv_kmh, "traction", "hold", threads};
}

constexpr const char* kFleetDoc =
    " model: 'power-flow' (default; power balance on a step_s grid), 'overlap' (overlap of "
    "braking and motoring intervals; overlap 'ahead' or 'either'), 'sections' (power flow per "
    "supply section, boundaries sections_at_m in m from the first station) or 'network' (a DC "
    "network from power_supply, a TOML file; step 0.1 s by default). The fleet: trains, span_s "
    "(first to last departure), headway_s (MIN, MAX whole s), trip_time_s (running and dwells), "
    "dwell_s at every stop within dwell_range_s; peaks [(FROM, TO), ...] with peak_headway_s and "
    "offpeak_headway_s. Every train drives one pattern: the optimal split of trip_time_s over "
    "the line's sections (grid ds_m, dv_kmh). threads: OpenMP threads (0: all).";

}  // namespace

void bind_timetable(py::module_& m) {
  py::module_ tt = m.def_submodule(
      "timetable", "Fleet timetables that use regenerated braking energy (question 2.1).");
  py::class_<PyFleet>(tt, "FleetResult",
                      "A fleet timetable's energy: substation = traction - regenerated energy "
                      "used by other trains, in kJ; power per bin in W.")
      .def_readonly("summary", &PyFleet::summary)
      .def(
          "to_dict", [](const PyFleet& f) { return to_python(f.report); },
          "The energy document of `ecorail timetable evaluate|optimise --json` (without the "
          "separation check's keys).")
      .def_property_readonly(
          "departures_s", [](const PyFleet& f) { return to_numpy(f.evaluation.departures_s); },
          "Departure of each train from the first station, s (int32).")
      .def_property_readonly(
          "headways_s",
          [](const PyFleet& f) {
            std::vector<int> h;
            for (std::size_t k = 1; k < f.evaluation.departures_s.size(); ++k)
              h.push_back(f.evaluation.departures_s[k] - f.evaluation.departures_s[k - 1]);
            return to_numpy(h);
          },
          "Headways between consecutive departures, s (int32).")
      .def_property_readonly(
          "substation_energy_kJ",
          [](const PyFleet& f) { return f.evaluation.total.substation_J() / 1e3; })
      .def_property_readonly("traction_energy_kJ",
                             [](const PyFleet& f) { return f.evaluation.total.traction_J / 1e3; })
      .def_property_readonly("regen_energy_kJ",
                             [](const PyFleet& f) { return f.evaluation.total.regen_J / 1e3; })
      .def_property_readonly("used_regen_kJ",
                             [](const PyFleet& f) { return f.evaluation.total.used_regen_J / 1e3; })
      .def_property_readonly(
          "per_train_substation_kJ",
          [](const PyFleet& f) {
            return to_numpy(per_train(
                f.evaluation, [](const timetable::FleetEnergy& e) { return e.substation_J(); }));
          },
          "Substation energy of each train, kJ (float64).")
      .def_property_readonly(
          "power_time_s",
          [](const PyFleet& f) {
            std::vector<double> t;
            for (std::size_t i = 0; i < f.traction_W.size(); ++i)
              t.push_back(f.trace_start_s + double(i) * f.trace_step_s);
            return to_numpy(t);
          },
          "Start of each power bin on the timetable clock, s (power-flow and sections models; "
          "empty otherwise).")
      .def_property_readonly(
          "traction_power_W", [](const PyFleet& f) { return to_numpy(f.traction_W); },
          "Traction power of all trains per bin, W.")
      .def_property_readonly(
          "regen_power_W", [](const PyFleet& f) { return to_numpy(f.regen_W); },
          "Regenerated power per bin, W.")
      .def_property_readonly(
          "used_regen_power_W", [](const PyFleet& f) { return to_numpy(f.used_W); },
          "Regenerated power used by other trains per bin, W.");

  py::class_<PyFleetLine>(tt, "Fleet",
                          "The line's sections, an energy model and the pattern every train "
                          "drives (the optimal split of trip_time_s with dwell_s at every stop), "
                          "built once: evaluate and optimise then cost only the timetable.")
      .def(py::init([](const PyLine& line, const PyTrain& train, const std::string& model,
                       const std::string& overlap, double step_s, std::vector<double> sections_at_m,
                       py::object power_supply, double trip_time_s, double dwell_s, double ds_m,
                       double dv_kmh, int threads) {
             FleetArgs a;
             add_fleet_args(a, model, overlap, step_s, std::move(sections_at_m),
                            std::move(power_supply), 100, 63900, {120, 660}, trip_time_s, dwell_s,
                            {30, 45}, {}, {120, 150}, {300, 660}, ds_m, dv_kmh, threads);
             return make_fleet(line, train, a);
           }),
           py::arg("line"), py::arg("train"), py::kw_only(), py::arg("model") = "power-flow",
           py::arg("overlap") = "ahead", py::arg("step_s") = NAN,
           py::arg("sections_at_m") = std::vector<double>{}, py::arg("power_supply") = py::none(),
           py::arg("trip_time_s") = 2086.0, py::arg("dwell_s") = 30.0, py::arg("ds_m") = 5.0,
           py::arg("dv_kmh") = 0.2, py::arg("threads") = 0)
      .def(
          "evaluate",
          [](const PyFleetLine& f, const py::object& departures_s, const py::object& headways_s,
             int trains, int span_s, Range headway_s, Range dwell_range_s, std::vector<Range> peaks,
             Range peak_headway_s, Range offpeak_headway_s) {
            return evaluate_py(f,
                               with_problem(f, trains, span_s, headway_s, dwell_range_s,
                                            std::move(peaks), peak_headway_s, offpeak_headway_s),
                               departures_s, headways_s);
          },
          py::kw_only(), py::arg("departures_s") = py::none(), py::arg("headways_s") = py::none(),
          py::arg("trains") = 100, py::arg("span_s") = 63900,
          py::arg("headway_s") = Range{120, 660}, py::arg("dwell_range_s") = Range{30, 45},
          py::arg("peaks") = std::vector<Range>{}, py::arg("peak_headway_s") = Range{120, 150},
          py::arg("offpeak_headway_s") = Range{300, 660},
          "ecorail.timetable.evaluate on this fleet's sections and pattern.")
      .def(
          "optimise",
          [](const PyFleetLine& f, int trains, int span_s, Range headway_s, Range dwell_range_s,
             std::vector<Range> peaks, Range peak_headway_s, Range offpeak_headway_s,
             std::uint64_t seed, double time_limit_s, int restarts, long moves,
             double anneal_step_s, const py::object& progress) {
            return optimise_py(f,
                               with_problem(f, trains, span_s, headway_s, dwell_range_s,
                                            std::move(peaks), peak_headway_s, offpeak_headway_s),
                               seed, time_limit_s, restarts, moves, anneal_step_s, progress);
          },
          py::kw_only(), py::arg("trains") = 100, py::arg("span_s") = 63900,
          py::arg("headway_s") = Range{120, 660}, py::arg("dwell_range_s") = Range{30, 45},
          py::arg("peaks") = std::vector<Range>{}, py::arg("peak_headway_s") = Range{120, 150},
          py::arg("offpeak_headway_s") = Range{300, 660}, py::arg("seed") = 1,
          py::arg("time_limit_s") = 0.0, py::arg("restarts") = 2, py::arg("moves") = 2000000L,
          py::arg("anneal_step_s") = 1.0, py::arg("progress") = py::none(),
          "ecorail.timetable.optimise on this fleet's sections and pattern.");

  tt.def(
      "evaluate",
      [](const PyLine& line, const PyTrain& train, const py::object& departures_s,
         const py::object& headways_s, const std::string& model, const std::string& overlap,
         double step_s, std::vector<double> sections_at_m, py::object power_supply, int trains,
         int span_s, Range headway_s, double trip_time_s, double dwell_s, Range dwell_range_s,
         std::vector<Range> peaks, Range peak_headway_s, Range offpeak_headway_s, double ds_m,
         double dv_kmh, int threads) {
        FleetArgs a;
        add_fleet_args(a, model, overlap, step_s, std::move(sections_at_m), std::move(power_supply),
                       trains, span_s, headway_s, trip_time_s, dwell_s, dwell_range_s,
                       std::move(peaks), peak_headway_s, offpeak_headway_s, ds_m, dv_kmh, threads);
        return evaluate_py(make_fleet(line, train, a), a, departures_s, headways_s);
      },
      py::arg("line"), py::arg("train"), py::kw_only(), py::arg("departures_s") = py::none(),
      py::arg("headways_s") = py::none(), py::arg("model") = "power-flow",
      py::arg("overlap") = "ahead", py::arg("step_s") = NAN,
      py::arg("sections_at_m") = std::vector<double>{}, py::arg("power_supply") = py::none(),
      py::arg("trains") = 100, py::arg("span_s") = 63900, py::arg("headway_s") = Range{120, 660},
      py::arg("trip_time_s") = 2086.0, py::arg("dwell_s") = 30.0,
      py::arg("dwell_range_s") = Range{30, 45}, py::arg("peaks") = std::vector<Range>{},
      py::arg("peak_headway_s") = Range{120, 150}, py::arg("offpeak_headway_s") = Range{300, 660},
      py::arg("ds_m") = 5.0, py::arg("dv_kmh") = 0.2, py::arg("threads") = 0,
      (std::string("The substation energy of a fleet timetable, as `ecorail timetable evaluate`: "
                   "departures_s (whole s from the first departure) or headways_s, or uniform "
                   "headways when neither is given.") +
       kFleetDoc)
          .c_str());
  tt.def(
      "optimise",
      [](const PyLine& line, const PyTrain& train, const std::string& model,
         const std::string& overlap, double step_s, std::vector<double> sections_at_m,
         py::object power_supply, int trains, int span_s, Range headway_s, double trip_time_s,
         double dwell_s, Range dwell_range_s, std::vector<Range> peaks, Range peak_headway_s,
         Range offpeak_headway_s, std::uint64_t seed, double time_limit_s, int restarts, long moves,
         double anneal_step_s, double ds_m, double dv_kmh, int threads,
         const py::object& progress) {
        FleetArgs a;
        add_fleet_args(a, model, overlap, step_s, std::move(sections_at_m), std::move(power_supply),
                       trains, span_s, headway_s, trip_time_s, dwell_s, dwell_range_s,
                       std::move(peaks), peak_headway_s, offpeak_headway_s, ds_m, dv_kmh, threads);
        return optimise_py(make_fleet(line, train, a), a, seed, time_limit_s, restarts, moves,
                           anneal_step_s, progress);
      },
      py::arg("line"), py::arg("train"), py::kw_only(), py::arg("model") = "power-flow",
      py::arg("overlap") = "ahead", py::arg("step_s") = NAN,
      py::arg("sections_at_m") = std::vector<double>{}, py::arg("power_supply") = py::none(),
      py::arg("trains") = 100, py::arg("span_s") = 63900, py::arg("headway_s") = Range{120, 660},
      py::arg("trip_time_s") = 2086.0, py::arg("dwell_s") = 30.0,
      py::arg("dwell_range_s") = Range{30, 45}, py::arg("peaks") = std::vector<Range>{},
      py::arg("peak_headway_s") = Range{120, 150}, py::arg("offpeak_headway_s") = Range{300, 660},
      py::arg("seed") = 1, py::arg("time_limit_s") = 0.0, py::arg("restarts") = 2,
      py::arg("moves") = 2000000L, py::arg("anneal_step_s") = 1.0, py::arg("ds_m") = 5.0,
      py::arg("dv_kmh") = 0.2, py::arg("threads") = 0, py::arg("progress") = py::none(),
      (std::string("The headways that minimise substation energy, as `ecorail timetable "
                   "optimise`: exact DPs for the overlap models, annealing (restarts, moves, "
                   "seed, anneal_step_s, time_limit_s in s; 0: none) + polish + a bound for "
                   "power-flow. A search stopped by time_limit_s is NO_CONVERGENCE with its "
                   "gap.") +
       kFleetDoc)
          .c_str());
}

}  // namespace ecorail::python
