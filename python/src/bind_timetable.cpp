// ecorail.timetable.evaluate / optimise / Fleet: fleet timetables that use regenerated braking
// energy (question 2.1), a thin wrapper over fleet::TimetableStudy, the object the program's
// `timetable` command drives (cli/cmd_timetable.cpp): the study solves the line's sections and
// the pattern every train drives and builds the energy model; to_dict() is the program's
// --json by output::timetable_evaluation_json / timetable_optimisation_json. A Fleet keeps one
// study and takes the study of each new fleet problem from it (TimetableStudy::with_problem,
// sharing the line's sections); optimise (headways, pattern, per-train patterns) runs
// TimetableStudy::optimise on a study of its own; separation runs the service simulator with
// safe separation (service/) and gives the energy JSON's "separation" block
// (output/separation_json.hpp).
#include <cmath>
#include <memory>
#include <mutex>
#include <tuple>

#include "data/route_builder.hpp"
#include "energy/model_registry.hpp"
#include "fleet/timetable_study.hpp"
#include "output/separation_json.hpp"
#include "output/timetable_json.hpp"
#include "power/supply_loader.hpp"
#include "python/src/common.hpp"
#include "service/pattern_service.hpp"

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

struct PyFleet {
  nlohmann::json report;
  energy::FleetEvaluation evaluation;
  PySummary summary;
  double trace_start_s = 0.0, trace_step_s = 0.0;
  std::vector<double> traction_W, regen_W, used_W;
};

// The fleet problem of a, checked as the program checks its flags (cli/timetable_options.cpp).
fleet::FleetProblem fleet_problem(const FleetArgs& a) {
  fleet::FleetProblem p;
  p.trains = a.trains;
  p.span_s = a.span_s;
  p.headway_min_s = whole_seconds("headway_s", a.headway_s.first);
  p.headway_max_s = whole_seconds("headway_s", a.headway_s.second);
  if (!(a.trip_time_s > 0.0))
    bad_argument("trip_time_s", "a trip time in s > 0", std::to_string(a.trip_time_s));
  p.trip_time_s = a.trip_time_s;
  p.dwell_min_s = a.dwell_range_s.first;
  p.dwell_max_s = a.dwell_range_s.second;
  for (const auto& [from, to] : a.peaks) {
    p.peak_windows.push_back({whole_seconds("peaks", from), whole_seconds("peaks", to)});
  }
  if (p.windowed()) {
    p.peak_headway_min_s = whole_seconds("peak_headway_s", a.peak_headway_s.first);
    p.peak_headway_max_s = whole_seconds("peak_headway_s", a.peak_headway_s.second);
    p.headway_min_s = whole_seconds("offpeak_headway_s", a.offpeak_headway_s.first);
    p.headway_max_s = whole_seconds("offpeak_headway_s", a.offpeak_headway_s.second);
  }
  require_valid(p);
  if (!(a.dwell_s >= p.dwell_min_s && a.dwell_s <= p.dwell_max_s)) {
    bad_argument("dwell_s", "a dwell within dwell_range_s", std::to_string(a.dwell_s));
  }
  return p;
}

// The energy model's options, checked as the program checks its flags.
energy::EnergyModelOptions model_options(const FleetArgs& a) {
  energy::EnergyModelOptions o;
  if (!energy::is_energy_model(a.model))
    bad_argument("model", energy::energy_model_names(), "'" + a.model + "'");
  o.model = a.model;
  const energy::ModelInputs reads = energy::model_inputs(a.model);
  const auto variant = energy::overlap_variant_from_name(a.overlap);
  if (!variant) bad_argument("overlap", "'ahead' or 'either'", "'" + a.overlap + "'");
  o.overlap = *variant;
  o.time_step_s = std::isnan(a.step_s) ? reads.default_time_step_s : a.step_s;
  o.section_boundaries_m = a.sections_at_m;
  // An argument the chosen model does not read is refused, never ignored (as the program's
  // flags; energy::ModelInputs).
  using energy::models_with, energy::ModelInputs;
  const std::string chosen = "model='" + a.model + "'";
  if (reads.power_supply) {
    if (a.power_supply.empty()) {
      bad_argument("power_supply", "a power-supply file (TOML) for " + chosen, "None");
    }
    o.power_supply =
        std::make_shared<const power::PowerSupply>(power::load_power_supply(a.power_supply));
  } else if (!a.power_supply.empty()) {
    bad_argument("power_supply",
                 "model=" + models_with(&ModelInputs::power_supply, "'") +
                     " (the other models have no supply network)",
                 "a file");
  }
  if (!a.sections_at_m.empty() && !reads.section_boundaries) {
    bad_argument("sections_at_m",
                 "model=" + models_with(&ModelInputs::section_boundaries, "'") +
                     " (the other models have no supply sections)",
                 chosen);
  }
  if (reads.section_boundaries && o.section_boundaries_m.empty()) {
    bad_argument("sections_at_m", "at least one supply-section boundary (m) for " + chosen, "none");
  }
  require_valid(o);
  return o;
}

// What a study is built from besides its problem: the line, the train, the run (first to last
// station), the grid, the pattern's dwell and the model.
struct StudyInputs {
  data::Line line;
  physics::Train train;
  dp::EngineOptions engine;
  double dwell_s = 30.0;
  energy::EnergyModelOptions model;
};

StudyInputs study_inputs(const PyLine& line, const PyTrain& train, const FleetArgs& a) {
  StudyInputs in{line.line, train.train, engine_options(a.engine, train), a.dwell_s,
                 model_options(a)};
  check_fleet_train(train);
  if (!(a.dwell_s >= 0.0)) bad_argument("dwell_s", "a dwell in s >= 0", std::to_string(a.dwell_s));
  require_valid(in.engine);
  return in;
}

// The study of one fleet problem: the line's sections, the pattern and the model (the GIL is
// released by the caller). Errors name the keyword argument as the program names its flag.
std::unique_ptr<fleet::TimetableStudy> make_study(const StudyInputs& in,
                                                  const fleet::FleetProblem& problem) {
  fleet::TimetableStudySetup setup;
  setup.line = in.line;
  setup.train = in.train;
  setup.stops =
      data::stops_between(in.line, in.line.stations.front().name, in.line.stations.back().name);
  setup.engine = in.engine;
  setup.dwell_s = in.dwell_s;
  setup.problem = problem;
  setup.model = in.model;
  try {
    return std::make_unique<fleet::TimetableStudy>(setup);
  } catch (const dp::InfeasibleTimeError& e) {
    bad_argument("trip_time_s",
                 "a trip time that leaves at least the flat-out running time of " +
                     std::to_string(e.minimum_s()) + " s after the dwells",
                 std::to_string(problem.trip_time_s));
  } catch (const std::invalid_argument& e) {
    // Options that do not fit the run: a section boundary or the supply beyond its end.
    const std::string what = e.what();
    if (what.rfind("section_boundaries_m: ", 0) == 0)
      throw std::invalid_argument("sections_at_m: " + what.substr(22));
    throw;
  }
}

bool same_problem(const fleet::FleetProblem& a, const fleet::FleetProblem& b) {
  if (a.peak_windows.size() != b.peak_windows.size()) return false;
  for (std::size_t i = 0; i < a.peak_windows.size(); ++i)
    if (a.peak_windows[i].from_s != b.peak_windows[i].from_s ||
        a.peak_windows[i].to_s != b.peak_windows[i].to_s)
      return false;
  return a.trains == b.trains && a.headway_min_s == b.headway_min_s &&
         a.headway_max_s == b.headway_max_s && a.span_s == b.span_s &&
         a.trip_time_s == b.trip_time_s && a.dwell_min_s == b.dwell_min_s &&
         a.dwell_max_s == b.dwell_max_s && a.peak_headway_min_s == b.peak_headway_min_s &&
         a.peak_headway_max_s == b.peak_headway_max_s;
}

// ecorail.timetable.Fleet: the inputs of the study and the study of the last problem asked for.
// A study holds one fleet problem (its model is built for that fleet); a call with another
// problem takes the study of that problem from it (TimetableStudy::with_problem): the line's
// sections are shared, only the model (and the pattern, when the trip time differs) is made.
struct FleetState {
  std::mutex mutex;  // one call at a time on a Fleet (its study is replaced by another problem)
  StudyInputs inputs;
  std::unique_ptr<fleet::TimetableStudy> study;
};

struct PyFleetLine {
  FleetArgs args;
  std::shared_ptr<FleetState> state;
};

// The inputs checked; the study is built by the first call (study_for).
std::shared_ptr<FleetState> fleet_state(const PyLine& line, const PyTrain& train,
                                        const FleetArgs& a) {
  auto state = std::make_shared<FleetState>();
  state->inputs = study_inputs(line, train, a);
  return state;
}

PyFleetLine make_fleet(const PyLine& line, const PyTrain& train, const FleetArgs& a) {
  PyFleetLine f{a, fleet_state(line, train, a)};
  const fleet::FleetProblem problem = fleet_problem(a);
  py::gil_scoped_release release;  // builds the line's sections and solves the pattern
  f.state->study = make_study(f.state->inputs, problem);
  return f;
}

// The Fleet's study for problem, built again when the problem differs from its study's; the
// caller holds the state's mutex and has released the GIL.
fleet::TimetableStudy& study_for(FleetState& state, const fleet::FleetProblem& problem) {
  if (!state.study) {
    state.study = make_study(state.inputs, problem);
  } else if (!same_problem(state.study->problem(), problem)) {
    state.study = state.study->with_problem(problem);
  }
  return *state.study;
}

// The power per bin over the day, for the models with a power balance.
void add_trace(PyFleet& out, const fleet::TimetableStudy& s, const std::vector<int>& departures) {
  if (!s.has_power_trace()) return;
  const double end_s =
      departures.empty() ? 0.0 : departures.back() + s.pattern().pattern.trip_time_s();
  const auto trace = s.power_trace(departures, 0.0, end_s);
  out.trace_start_s = trace.start_s;
  out.trace_step_s = trace.step_s;
  out.traction_W = trace.traction_W;
  out.regen_W = trace.regen_W;
  out.used_W = trace.used_W;
}

std::vector<int> given_departures(const fleet::FleetProblem& p, const py::object& departures_s,
                                  const py::object& headways_s) {
  if (!departures_s.is_none() && !headways_s.is_none()) {
    bad_argument("departures_s", "either departures_s or headways_s, not both", "both");
  }
  std::vector<int> t;
  if (!departures_s.is_none()) {
    for (const auto& v : departures_s)
      t.push_back(whole_seconds("departures_s", py::cast<double>(v)));
  } else if (!headways_s.is_none()) {
    std::vector<int> h;
    for (const auto& v : headways_s) h.push_back(whole_seconds("headways_s", py::cast<double>(v)));
    t = fleet::departures_from_headways(h);
  } else {
    t = fleet::departures_from_headways(fleet::uniform_headways(p));
  }
  const std::string why = fleet::departures_problem(p, t);
  if (!why.empty())
    bad_argument(departures_s.is_none() ? "headways_s" : "departures_s",
                 "departures that keep the problem", why);
  return t;
}

PyFleet evaluate_py(FleetState& state, const FleetArgs& a, const py::object& departures_s,
                    const py::object& headways_s) {
  const fleet::FleetProblem problem = fleet_problem(a);
  // The departures are checked before the line's sections are built: bad ones fail fast.
  const std::vector<int> departures = given_departures(problem, departures_s, headways_s);
  PyFleet out;
  {
    py::gil_scoped_release release;
    std::lock_guard<std::mutex> lock(state.mutex);
    const fleet::TimetableStudy& s = study_for(state, problem);
    const fleet::StudyEvaluation e = s.evaluate(departures);
    out.evaluation = e.evaluation;
    out.report = output::timetable_evaluation_json(s, e);
    add_trace(out, s, departures);
  }
  out.summary.termination = dp::Termination::CONVERGENCE;
  return out;
}

// The search optimise() runs, from its keyword arguments (search_kwargs below): the library's
// own options, as `timetable optimise` binds its flags to them. pattern: the dwells and running
// times too (`--optimise pattern`); per_train_patterns implies it.
fleet::StudyOptimiseOptions search_options(std::uint64_t seed, double time_limit_s, int restarts,
                                           int rounds, long moves, double anneal_step_s, double gap,
                                           bool pattern, bool per_train_patterns) {
  fleet::StudyOptimiseOptions so;
  so.headways.seed = seed;
  so.headways.restarts = restarts;
  so.headways.moves_per_run = moves;
  so.headways.anneal_step_s = anneal_step_s;
  so.headways.time_limit_s = time_limit_s;
  so.headways.gap_fraction = gap;
  so.headways.rounds = rounds;
  so.pattern = pattern || per_train_patterns;
  so.per_train_patterns = per_train_patterns;
  return so;
}

// departures_s / headways_s (None: none): a timetable the search starts from too, whose used
// energy the result never falls below (`timetable optimise --departures/--headways`).
PyFleet optimise_py(FleetState& state, const FleetArgs& a, fleet::StudyOptimiseOptions so,
                    const py::object& departures_s, const py::object& headways_s,
                    const py::object& progress) {
  const fleet::FleetProblem problem = fleet_problem(a);
  fleet::HeadwayOptimiserOptions& o = so.headways;
  if (!departures_s.is_none() || !headways_s.is_none()) {
    const char* field = departures_s.is_none() ? "headways_s" : "departures_s";
    if (so.pattern)
      bad_argument(field,
                   "pattern=False and per_train_patterns=False (a given timetable is a start for "
                   "the headway search, whose pattern is fixed)",
                   "a pattern search");
    o.given_starts_s = {given_departures(problem, departures_s, headways_s)};
  }
  o.threads = a.engine.threads;
  if (so.per_train_patterns && energy::is_energy_model(a.model) &&
      !energy::model_inputs(a.model).per_train_trips) {
    bad_argument("per_train_patterns",
                 "model=" + energy::models_with(&energy::ModelInputs::per_train_trips, "'") +
                     " (the per-train search prices one train's pattern against the fleet's "
                     "power balance)",
                 "model='" + a.model + "'");
  }
  require_valid(so);
  Interruptible guard(progress);
  const dp::ProgressFn check = guard.callback();
  o.progress = [&check](const fleet::OptimiserProgress& p) { check(p.stage.c_str(), 0, 0); };
  so.pattern_progress = [&check](const fleet::PatternProgress& p) { check(p.stage.c_str(), 0, 0); };
  PyFleet out;
  std::string message;
  bool usable = false;  // the optimiser's own test: a budget-stopped search is a result
  guard.run([&] {
    std::lock_guard<std::mutex> lock(state.mutex);
    // A study of its own (sharing the Fleet's sections): a pattern search keeps the pattern it
    // found in the study it ran on, never in the Fleet's.
    const std::unique_ptr<fleet::TimetableStudy> s =
        study_for(state, problem).with_problem(problem);
    const fleet::StudyOptimisation r = s->optimise(so);
    out.evaluation = r.result.evaluation;
    out.report = output::timetable_optimisation_json(*s, r, o.seed);
    const auto& sm = r.result.summary;
    out.summary = summary_of(sm);
    message = sm.message;
    usable = sm.IsSolutionUsable();
    if (usable) add_trace(out, *s, r.result.evaluation.departures_s);
    return 0;
  });
  if (!usable) {
    raise_solve_error("the optimiser failed: " + message, py::cast(out));
  }
  return out;
}

// The timetable's trains run together with safe separation (`timetable evaluate --separation`).
struct PySeparation {
  nlohmann::json report;  // the energy JSON's "separation" block
  service::ServiceSummary summary;
};

PySeparation separation_py(FleetState& state, const FleetArgs& a, const py::object& departures_s,
                           const py::object& headways_s, double train_length_m,
                           double safety_margin_m, double braking_m_s2, const std::string& follower,
                           const py::object& progress) {
  const fleet::FleetProblem problem = fleet_problem(a);
  const std::vector<int> departures = given_departures(problem, departures_s, headways_s);
  service::ServiceOptions o;
  o.separation.train_length_m = train_length_m;
  o.separation.safety_margin_m = safety_margin_m;
  o.separation.braking_m_s2 = braking_m_s2;
  const auto mode = service::follower_mode_from_name(follower);
  if (!mode) bad_argument("follower", "'reoptimise', 'supervise' or 'wait'", "'" + follower + "'");
  o.mode = *mode;
  require_valid(o);
  // Ctrl-C (and the user's progress callable) is seen after each train.
  Interruptible guard(progress);
  o.progress = guard.callback();
  PySeparation out;
  guard.run([&] {
    std::lock_guard<std::mutex> lock(state.mutex);
    const fleet::TimetableStudy& s = study_for(state, problem);
    const fleet::FleetPattern& pattern = s.pattern().pattern;
    const service::ServiceResult r = service::simulate_service(
        s.library(),
        service::plan_from_running_times(s.library(), pattern.running_times_s, pattern.dwells_s),
        std::vector<double>(departures.begin(), departures.end()), o);
    out.report = output::separation_json(r, o);
    out.summary = r.summary;
  });
  if (out.summary.cap_exceeded) {
    raise_solve_error("a simulated train exceeds the separation cap: " + out.summary.BriefReport(),
                      py::cast(out));
  }
  return out;
}

// The fleet problem's arguments (trains, span, headways, dwell range, peaks) into a.
void set_problem(FleetArgs& a, int trains, int span_s, Range headway_s, Range dwell_range_s,
                 std::vector<Range> peaks, Range peak_headway_s, Range offpeak_headway_s) {
  a.trains = trains;
  a.span_s = span_s;
  a.headway_s = headway_s;
  a.dwell_range_s = dwell_range_s;
  a.peaks = std::move(peaks);
  a.peak_headway_s = peak_headway_s;
  a.offpeak_headway_s = offpeak_headway_s;
}

// The fleet's arguments with the problem's own (trains, span, headways, peaks).
FleetArgs with_problem(const PyFleetLine& f, int trains, int span_s, Range headway_s,
                       Range dwell_range_s, std::vector<Range> peaks, Range peak_headway_s,
                       Range offpeak_headway_s) {
  FleetArgs a = f.args;
  set_problem(a, trains, span_s, headway_s, dwell_range_s, std::move(peaks), peak_headway_s,
              offpeak_headway_s);
  return a;
}

std::vector<double> per_train(const energy::FleetEvaluation& ev,
                              double (*f)(const energy::FleetEnergy&)) {
  std::vector<double> v;
  for (const auto& e : ev.per_train) v.push_back(f(e) / 1e3);
  return v;
}

// The model, the run and the grid of a fleet (model_kwargs, run_kwargs, grid_kwargs below) into
// a; its problem keeps FleetArgs' defaults (set_problem sets it).
void add_fleet_args(FleetArgs& a, const std::string& model, const std::string& overlap,
                    double step_s, std::vector<double> sections_at_m, py::object power_supply,
                    double trip_time_s, double dwell_s, double ds_m, double dv_kmh, int threads) {
  a.model = model;
  a.overlap = overlap;
  a.step_s = step_s;
  a.sections_at_m = std::move(sections_at_m);
  if (!power_supply.is_none()) {
    a.power_supply = fspath(power_supply);
  }
  a.trip_time_s = trip_time_s;
  a.dwell_s = dwell_s;
  a.engine = {ds_m, dv_kmh, "traction", "hold", threads};
}

// The keyword arguments the fleet functions share, each group written once with its defaults
// (FleetArgs' and the library's); every function's lambda takes a group's values in its order.
auto model_kwargs() {  // model, overlap, step_s, sections_at_m, power_supply
  const FleetArgs d;
  return std::make_tuple(
      py::arg("model") = d.model, py::arg("overlap") = d.overlap, py::arg("step_s") = d.step_s,
      py::arg("sections_at_m") = std::vector<double>{}, py::arg("power_supply") = py::none());
}
auto run_kwargs() {  // trip_time_s, dwell_s
  const FleetArgs d;
  return std::make_tuple(py::arg("trip_time_s") = d.trip_time_s, py::arg("dwell_s") = d.dwell_s);
}
auto problem_kwargs() {  // trains, span_s, headway_s, dwell_range_s, peaks, peak/offpeak_headway_s
  const FleetArgs d;
  return std::make_tuple(
      py::arg("trains") = d.trains, py::arg("span_s") = d.span_s,
      py::arg("headway_s") = d.headway_s, py::arg("dwell_range_s") = d.dwell_range_s,
      py::arg("peaks") = std::vector<Range>{}, py::arg("peak_headway_s") = d.peak_headway_s,
      py::arg("offpeak_headway_s") = d.offpeak_headway_s);
}
auto grid_kwargs() {  // ds_m, dv_kmh, threads
  const EngineArgs d;
  return std::make_tuple(py::arg("ds_m") = d.ds_m, py::arg("dv_kmh") = d.dv_kmh,
                         py::arg("threads") = d.threads);
}
auto search_kwargs() {  // seed, time_limit_s, restarts, rounds, moves, anneal_step_s, gap,
                        // pattern, per_train_patterns
  const fleet::StudyOptimiseOptions d;
  return std::make_tuple(
      py::arg("seed") = d.headways.seed, py::arg("time_limit_s") = d.headways.time_limit_s,
      py::arg("restarts") = d.headways.restarts, py::arg("rounds") = d.headways.rounds,
      py::arg("moves") = d.headways.moves_per_run,
      py::arg("anneal_step_s") = d.headways.anneal_step_s, py::arg("gap") = d.headways.gap_fraction,
      py::arg("pattern") = d.pattern, py::arg("per_train_patterns") = d.per_train_patterns);
}

auto start_kwargs() {  // departures_s, headways_s: a timetable optimise() also starts from
  return std::make_tuple(py::arg("departures_s") = py::none(), py::arg("headways_s") = py::none());
}

// target.def(name, f, extras...) with the extras given as tuples (the kwargs groups above).
template <class Target, class F, class... Groups>
void def_with(Target& target, const char* name, F&& f, Groups&&... groups) {
  std::apply([&](auto&&... extra) { target.def(name, std::forward<F>(f), extra...); },
             std::tuple_cat(std::forward<Groups>(groups)...));
}
// The same for a constructor (py::init).
template <class Class, class Init, class... Groups>
void def_init_with(Class& cls, Init&& init, Groups&&... groups) {
  std::apply([&](auto&&... extra) { cls.def(std::forward<Init>(init), extra...); },
             std::tuple_cat(std::forward<Groups>(groups)...));
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
                f.evaluation, [](const energy::FleetEnergy& e) { return e.substation_J(); }));
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

  py::class_<PySeparation>(tt, "SeparationResult",
                           "Every train of a timetable run together with safe separation: the "
                           "least margins to the cap, where it binds and how held-up followers "
                           "were driven; energies in kJ, times in s, distances in m.")
      .def(
          "to_dict", [](const PySeparation& r) { return to_python(r.report); },
          "The \"separation\" block of `ecorail timetable evaluate --separation --json`.")
      .def_property_readonly("brief_report",
                             [](const PySeparation& r) { return r.summary.BriefReport(); })
      .def_property_readonly(
          "min_speed_margin_kmh",
          [](const PySeparation& r) { return r.summary.min_speed_margin_kmh; },
          "Least margin of any train's speed below the cap, km/h.")
      .def_property_readonly(
          "min_distance_margin_m",
          [](const PySeparation& r) { return r.summary.min_distance_margin_m; },
          "Least margin of any train's braking distance to the train ahead, m.")
      .def_property_readonly("trains_resimulated",
                             [](const PySeparation& r) { return r.summary.trains_resimulated; })
      .def_property_readonly(
          "max_late_s", [](const PySeparation& r) { return r.summary.max_late_s; },
          "Latest arrival at a stop after the timetable, s.");

  py::class_<PyFleetLine> fleet_class(
      tt, "Fleet",
      "The line's sections, an energy model and the pattern every train drives (the optimal "
      "split of trip_time_s with dwell_s at every stop), built once: evaluate and optimise then "
      "cost only the timetable.");
  def_init_with(
      fleet_class,
      py::init([](const PyLine& line, const PyTrain& train, const std::string& model,
                  const std::string& overlap, double step_s, std::vector<double> sections_at_m,
                  py::object power_supply, double trip_time_s, double dwell_s, double ds_m,
                  double dv_kmh, int threads) {
        FleetArgs a;
        add_fleet_args(a, model, overlap, step_s, std::move(sections_at_m), std::move(power_supply),
                       trip_time_s, dwell_s, ds_m, dv_kmh, threads);
        return make_fleet(line, train, a);
      }),
      std::make_tuple(py::arg("line"), py::arg("train"), py::kw_only()), model_kwargs(),
      run_kwargs(), grid_kwargs());
  def_with(
      fleet_class, "evaluate",
      [](const PyFleetLine& f, const py::object& departures_s, const py::object& headways_s,
         int trains, int span_s, Range headway_s, Range dwell_range_s, std::vector<Range> peaks,
         Range peak_headway_s, Range offpeak_headway_s) {
        return evaluate_py(*f.state,
                           with_problem(f, trains, span_s, headway_s, dwell_range_s,
                                        std::move(peaks), peak_headway_s, offpeak_headway_s),
                           departures_s, headways_s);
      },
      std::make_tuple(py::kw_only(), py::arg("departures_s") = py::none(),
                      py::arg("headways_s") = py::none()),
      problem_kwargs(),
      std::make_tuple("ecorail.timetable.evaluate on this fleet's sections and pattern."));
  def_with(
      fleet_class, "optimise",
      [](const PyFleetLine& f, int trains, int span_s, Range headway_s, Range dwell_range_s,
         std::vector<Range> peaks, Range peak_headway_s, Range offpeak_headway_s,
         std::uint64_t seed, double time_limit_s, int restarts, int rounds, long moves,
         double anneal_step_s, double gap, bool pattern, bool per_train_patterns,
         const py::object& departures_s, const py::object& headways_s, const py::object& progress) {
        return optimise_py(*f.state,
                           with_problem(f, trains, span_s, headway_s, dwell_range_s,
                                        std::move(peaks), peak_headway_s, offpeak_headway_s),
                           search_options(seed, time_limit_s, restarts, rounds, moves,
                                          anneal_step_s, gap, pattern, per_train_patterns),
                           departures_s, headways_s, progress);
      },
      std::make_tuple(py::kw_only()), problem_kwargs(), search_kwargs(), start_kwargs(),
      std::make_tuple(py::arg("progress") = py::none(),
                      "ecorail.timetable.optimise on this fleet's sections and pattern (the Fleet "
                      "keeps its own pattern: a pattern search runs on a study of its own)."));
  fleet_class.def(
      "separation",
      [](const PyFleetLine& f, const py::object& departures_s, const py::object& headways_s,
         int trains, int span_s, Range headway_s, double train_length_m, double safety_margin_m,
         double braking_m_s2, const std::string& follower, const py::object& progress) {
        FleetArgs a = with_problem(f, trains, span_s, headway_s, f.args.dwell_range_s, {},
                                   f.args.peak_headway_s, f.args.offpeak_headway_s);
        return separation_py(*f.state, a, departures_s, headways_s, train_length_m, safety_margin_m,
                             braking_m_s2, follower, progress);
      },
      py::kw_only(), py::arg("departures_s") = py::none(), py::arg("headways_s") = py::none(),
      py::arg("trains") = 100, py::arg("span_s") = 63900, py::arg("headway_s") = Range{120, 660},
      py::arg("train_length_m") = 0.0, py::arg("safety_margin_m") = 0.0,
      py::arg("braking_m_s2") = 0.0, py::arg("follower") = "reoptimise",
      py::arg("progress") = py::none(),
      "Every train of the timetable run together with safe separation v <= sqrt(2 L b), as "
      "`ecorail timetable evaluate --separation`: L the distance to the train ahead's tail "
      "less safety_margin_m (train_length_m, m), b = braking_m_s2 (0: the train's maximum "
      "braking force at 10 km/h over its mass); a follower held up where waiting would "
      "make it late is driven by follower: 'reoptimise' (energy-optimal under the cap), "
      "'supervise' (its planned control, braked) or 'wait'. progress(stage, done, total) is "
      "called after each train (Ctrl-C stops the run there). to_dict() is the energy "
      "document's \"separation\" block.");

  const std::string evaluate_doc =
      std::string(
          "The substation energy of a fleet timetable, as `ecorail timetable evaluate`: "
          "departures_s (whole s from the first departure) or headways_s, or uniform "
          "headways when neither is given.") +
      kFleetDoc;
  def_with(
      tt, "evaluate",
      [](const PyLine& line, const PyTrain& train, const py::object& departures_s,
         const py::object& headways_s, const std::string& model, const std::string& overlap,
         double step_s, std::vector<double> sections_at_m, py::object power_supply,
         double trip_time_s, double dwell_s, int trains, int span_s, Range headway_s,
         Range dwell_range_s, std::vector<Range> peaks, Range peak_headway_s,
         Range offpeak_headway_s, double ds_m, double dv_kmh, int threads) {
        FleetArgs a;
        add_fleet_args(a, model, overlap, step_s, std::move(sections_at_m), std::move(power_supply),
                       trip_time_s, dwell_s, ds_m, dv_kmh, threads);
        set_problem(a, trains, span_s, headway_s, dwell_range_s, std::move(peaks), peak_headway_s,
                    offpeak_headway_s);
        return evaluate_py(*fleet_state(line, train, a), a, departures_s, headways_s);
      },
      std::make_tuple(py::arg("line"), py::arg("train"), py::kw_only(),
                      py::arg("departures_s") = py::none(), py::arg("headways_s") = py::none()),
      model_kwargs(), run_kwargs(), problem_kwargs(), grid_kwargs(),
      std::make_tuple(evaluate_doc.c_str()));
  const std::string optimise_doc =
      std::string(
          "The headways that minimise substation energy, as `ecorail timetable "
          "optimise`: exact DPs for the overlap models, annealing (restarts, moves, "
          "seed, anneal_step_s, time_limit_s in s; 0: none) + polish + a bound for "
          "power-flow. CONVERGENCE only when the proven gap is at most gap (a fraction of "
          "the substation energy); a search stopped by time_limit_s or its moves with a "
          "larger gap is NO_CONVERGENCE with its gap (a result: is_solution_usable). "
          "pattern: the dwells and running times too (`--optimise pattern`); "
          "per_train_patterns: each train its own pattern (power-flow and sections "
          "models). departures_s or headways_s: a timetable to start from too "
          "(`--departures`/`--headways`); the result never uses less regenerated energy "
          "than it (summary given_start_used_regen_kJ in to_dict()).") +
      kFleetDoc;
  def_with(
      tt, "optimise",
      [](const PyLine& line, const PyTrain& train, const std::string& model,
         const std::string& overlap, double step_s, std::vector<double> sections_at_m,
         py::object power_supply, double trip_time_s, double dwell_s, int trains, int span_s,
         Range headway_s, Range dwell_range_s, std::vector<Range> peaks, Range peak_headway_s,
         Range offpeak_headway_s, double ds_m, double dv_kmh, int threads, std::uint64_t seed,
         double time_limit_s, int restarts, int rounds, long moves, double anneal_step_s,
         double gap, bool pattern, bool per_train_patterns, const py::object& departures_s,
         const py::object& headways_s, const py::object& progress) {
        FleetArgs a;
        add_fleet_args(a, model, overlap, step_s, std::move(sections_at_m), std::move(power_supply),
                       trip_time_s, dwell_s, ds_m, dv_kmh, threads);
        set_problem(a, trains, span_s, headway_s, dwell_range_s, std::move(peaks), peak_headway_s,
                    offpeak_headway_s);
        return optimise_py(*fleet_state(line, train, a), a,
                           search_options(seed, time_limit_s, restarts, rounds, moves,
                                          anneal_step_s, gap, pattern, per_train_patterns),
                           departures_s, headways_s, progress);
      },
      std::make_tuple(py::arg("line"), py::arg("train"), py::kw_only()), model_kwargs(),
      run_kwargs(), problem_kwargs(), grid_kwargs(), search_kwargs(), start_kwargs(),
      std::make_tuple(py::arg("progress") = py::none(), optimise_doc.c_str()));
}

}  // namespace ecorail::python
