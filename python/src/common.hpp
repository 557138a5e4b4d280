// What every binding file of the Python module shares: the loaded line and train (with where
// they came from, for the reports' provenance), the conversion of library JSON and per-second
// tables to Python, options checked by their IsValid (ValueError with the library's sentence),
// and running library work with the GIL released while Ctrl-C can stop it between stages.
#pragma once

#include <pybind11/eval.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "data/line.hpp"
#include "dp/progress_callback.hpp"
#include "dp/section_engine.hpp"
#include "dp/termination.hpp"
#include "output/solve_reports.hpp"
#include "output/timeline.hpp"
#include "physics/train.hpp"

namespace ecorail::python {

namespace py = pybind11;

// A line as loaded, with the label its reports name it by ("embedded" or the path given).
struct PyLine {
  data::Line line;
  std::string source = "embedded";
};

// A train as loaded, with its label ("embedded" or the path given).
struct PyTrain {
  physics::Train train;
  std::string source = "embedded";
};

// An options struct refused by its IsValid: ValueError "invalid options: <sentence>".
class InvalidOptions : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

template <typename Options>
void require_valid(const Options& options) {
  std::string why;
  if (!options.IsValid(&why)) throw InvalidOptions("invalid options: " + why);
}

// A path argument (str, bytes or os.PathLike) as text: os.fspath(path).
std::string fspath(const py::object& path);

// ValueError naming a keyword argument: "<field>: expected <what>; got <got>".
[[noreturn]] void bad_argument(const std::string& field, const std::string& expected,
                               const std::string& got);

// The argument checks the fleet, delay and Monte Carlo functions share, each a ValueError
// naming its keyword argument (bad_argument): value within [min, max] (and finite), an integer
// within [min, max], whole seconds (|v| <= 1e9), and a train the fleet models can run
// (constant efficiencies).
void check_range(const std::string& field, double value, double min, double max,
                 const std::string& expected);
void check_count(const std::string& field, long long value, long long min, long long max,
                 const std::string& expected);
int whole_seconds(const std::string& field, double value);
void check_fleet_train(const PyTrain& train);

// A library JSON document as Python objects (dict, list, int, float, str, bool, None).
py::object to_python(const nlohmann::json& j);

// The per-second table (output::per_second) as named numpy arrays: time_s, position_m,
// speed_ms, accel_m_s2, traction_N, braking_N, power_W (traction power), km_post_m,
// gradient_permille, speed_limit_ms (float64), section (int32), regime (str).
struct Arrays {
  std::vector<double> time_s, position_m, speed_ms, accel_m_s2, traction_N, braking_N, power_W,
      km_post_m, gradient_permille, speed_limit_ms;
  std::vector<int> section;
  std::vector<std::string> regime;
};
Arrays per_second_arrays(const output::Timeline& timeline);
py::array_t<double> to_numpy(const std::vector<double>& v);
py::array_t<int> to_numpy(const std::vector<int>& v);
py::array to_numpy(const std::vector<std::string>& v);  // numpy str array ('<U..')

// How a solve ended, as a Python object: termination (ecorail.Termination), brief_report,
// full_report, warnings, is_solution_usable. Usable is what the library's summary says
// (IsSolutionUsable, dp/termination.hpp's one rule: the result keeps every constraint). A
// summary made without a library summary falls back to dp::is_usable of its termination.
struct PySummary {
  dp::Termination termination = dp::Termination::FAILURE;
  std::string brief_report, full_report;
  std::vector<std::string> warnings;
  std::optional<bool> usable;  // the library summary's IsSolutionUsable()
  bool is_solution_usable() const { return usable.value_or(dp::is_usable(termination)); }
};

// The PySummary of a library summary (Termination, BriefReport, FullReport, IsSolutionUsable).
template <typename Summary>
PySummary summary_of(const Summary& s, std::vector<std::string> warnings = {}) {
  return {s.termination, s.BriefReport(), s.FullReport(), std::move(warnings),
          s.IsSolutionUsable()};
}

// Thrown through library code by the progress callback when Python asked to stop (Ctrl-C, or
// the user's progress callback raised); the Python error is kept and raised again once the GIL
// is held.
struct Cancelled {};

// A progress callback for library options: on the thread that called into Python and outside
// any parallel region it takes the GIL, runs the signal handlers (PyErr_CheckSignals) and the
// user's progress callable if one was given, and unwinds the library work with Cancelled when
// either raised. Elsewhere (OpenMP workers) it does nothing.
class Interruptible {
 public:
  explicit Interruptible(py::object user_progress = py::none());
  dp::ProgressFn callback();
  // Runs f with the GIL released; a Cancelled unwinding from it becomes the Python error that
  // caused it (KeyboardInterrupt for Ctrl-C).
  template <typename F>
  auto run(F&& f) -> decltype(f()) {
    try {
      py::gil_scoped_release release;
      return f();
    } catch (const Cancelled&) {
      raise_pending();
    }
  }
  // A check between stages of work done with the GIL held.
  void check();

 private:
  [[noreturn]] void raise_pending();
  void poll();  // with the GIL held
  py::object user_progress_;
  std::thread::id owner_;
  std::optional<py::error_already_set> pending_;
};

// Raises ecorail.SolveError(message, result): a result that misses its stop, its time or a
// window, never returned as if it were one.
[[noreturn]] void raise_solve_error(const std::string& message, py::object result);

// The provenance inputs of a run on line and train.
output::RunInputs run_inputs(const PyLine& line, const PyTrain& train, const std::string& from,
                             const std::string& to, const std::string& objective, double ds_m,
                             double dv_kmh);

// Engine options from keyword arguments (ds_m, dv_kmh, objective, cruise, threads); checked by
// the caller's require_valid. objective and cruise must be names the program accepts.
struct EngineArgs {
  double ds_m = 5.0;
  double dv_kmh = 0.2;
  std::string objective = "traction";
  std::string cruise = "hold";
  int threads = 0;
};
dp::EngineOptions engine_options(const EngineArgs& a, const PyTrain& train);

void bind_common(py::module_& m);
void bind_model(py::module_& m);
void bind_solve(py::module_& m);
void bind_policy(py::module_& m);
void bind_fitting(py::module_& m);
void bind_timetable(py::module_& m);
void bind_delay(py::module_& m);
void bind_montecarlo(py::module_& m);

}  // namespace ecorail::python
