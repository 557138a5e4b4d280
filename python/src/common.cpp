#include "python/src/common.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>

#include "data/csv_reader.hpp"
#include "data/input_error.hpp"
#include "data/train_io.hpp"
#include "dp/journey_plan.hpp"
#include "dp/resource_estimate.hpp"
#include "dp/text_format.hpp"
#include "dp/time_target.hpp"
#include "fitting/calibration.hpp"
#include "physics/units.hpp"
#include "policy/advisor.hpp"
#include "policy/ladder.hpp"
#include "policy/policy_table.hpp"
#include "recovery/delay_recovery.hpp"

namespace ecorail::python {

void bad_argument(const std::string& field, const std::string& expected, const std::string& got) {
  throw py::value_error(field + ": expected " + expected + "; got " + got);
}

std::string fspath(const py::object& path) {
  return py::str(py::module_::import("os").attr("fspath")(path));
}

py::object to_python(const nlohmann::json& j) {
  switch (j.type()) {
    case nlohmann::json::value_t::null:
      return py::none();
    case nlohmann::json::value_t::boolean:
      return py::bool_(j.get<bool>());
    case nlohmann::json::value_t::number_integer:
      return py::int_(j.get<std::int64_t>());
    case nlohmann::json::value_t::number_unsigned:
      return py::int_(j.get<std::uint64_t>());
    case nlohmann::json::value_t::number_float: {
      // A non-finite number is null in the command's JSON file (nlohmann writes it so), and so
      // None here: to_dict() equals the file, field for field.
      const double v = j.get<double>();
      return std::isfinite(v) ? py::object(py::float_(v)) : py::object(py::none());
    }
    case nlohmann::json::value_t::string:
      return py::str(j.get_ref<const std::string&>());
    case nlohmann::json::value_t::array: {
      py::list list;
      for (const auto& item : j) list.append(to_python(item));
      return list;
    }
    case nlohmann::json::value_t::object: {
      py::dict dict;
      for (const auto& [key, value] : j.items()) dict[py::str(key)] = to_python(value);
      return dict;
    }
    default:
      return py::none();
  }
}

Arrays per_second_arrays(const output::Timeline& timeline) {
  const output::Timeline rows = output::per_second(timeline);
  Arrays a;
  for (const auto& r : rows) {
    const double traction_N = std::max(0.0, r.force_N);
    a.time_s.push_back(r.t_s);
    a.position_m.push_back(r.s_m);
    a.speed_ms.push_back(r.v_ms);
    a.accel_m_s2.push_back(r.accel_m_s2);
    a.traction_N.push_back(traction_N);
    a.braking_N.push_back(std::max(0.0, -r.force_N));
    a.power_W.push_back(traction_N * r.v_ms);
    a.km_post_m.push_back(r.km_post_m);
    a.gradient_permille.push_back(r.gradient_permille);
    a.speed_limit_ms.push_back(r.speed_limit_ms);
    a.section.push_back(r.section);
    // The CSV's label: a dwell is "dwell", a run its regime.
    a.regime.push_back(r.dwelling ? "dwell" : std::string(physics::regime_name(r.regime)));
  }
  return a;
}

py::array_t<double> to_numpy(const std::vector<double>& v) {
  py::array_t<double> out(static_cast<py::ssize_t>(v.size()));
  std::copy(v.begin(), v.end(), out.mutable_data());
  return out;
}

py::array_t<int> to_numpy(const std::vector<int>& v) {
  py::array_t<int> out(static_cast<py::ssize_t>(v.size()));
  std::copy(v.begin(), v.end(), out.mutable_data());
  return out;
}

py::array to_numpy(const std::vector<std::string>& v) {
  py::list list;
  for (const auto& s : v) list.append(py::str(s));
  return py::module_::import("numpy").attr("array")(list, py::arg("dtype") = "str");
}

Interruptible::Interruptible(py::object user_progress)
    : user_progress_(std::move(user_progress)), owner_(std::this_thread::get_id()) {}

void Interruptible::poll() {
  if (PyErr_CheckSignals() != 0) {
    pending_.emplace();  // fetches the error the signal handler raised
    throw Cancelled{};
  }
}

void Interruptible::check() {
  try {
    poll();
  } catch (const Cancelled&) {
    raise_pending();
  }
}

dp::ProgressFn Interruptible::callback() {
  return [this](const char* stage, int done, int total) {
    // Only where unwinding is safe: the calling thread, outside OpenMP regions.
    if (std::this_thread::get_id() != owner_ || omp_in_parallel()) return;
    py::gil_scoped_acquire gil;
    poll();
    if (!user_progress_.is_none()) {
      try {
        user_progress_(stage, done, total);
      } catch (py::error_already_set& e) {
        e.restore();
        pending_.emplace();
        throw Cancelled{};
      }
    }
  };
}

void Interruptible::raise_pending() {
  if (!pending_) throw std::logic_error("ecorail: cancelled without a Python error");
  py::error_already_set error = std::move(*pending_);
  pending_.reset();
  throw error;
}

void raise_solve_error(const std::string& message, py::object result) {
  py::object type = py::module_::import("ecorail._ecorail").attr("SolveError");
  py::object error = type(message, result);
  PyErr_SetObject(type.ptr(), error.ptr());
  throw py::error_already_set();
}

output::RunInputs run_inputs(const PyLine& line, const PyTrain& train, const std::string& from,
                             const std::string& to, const std::string& objective, double ds_m,
                             double dv_kmh) {
  output::RunInputs in;
  in.line = line.source;
  in.train = train.source;
  in.from = from;
  in.to = to;
  in.objective = objective;
  in.ds_m = ds_m;
  in.dv_kmh = dv_kmh;
  return in;
}

dp::EngineOptions engine_options(const EngineArgs& a, const PyTrain& train) {
  dp::EngineOptions e;
  e.grid.ds_m = a.ds_m;
  e.grid.dv_kmh = a.dv_kmh;
  e.grid.substep_m = 0.5 * a.ds_m;
  const auto objective = dp::objective_from_name(a.objective);
  if (!objective) bad_argument("objective", "'traction' or 'net'", "'" + a.objective + "'");
  e.objective = *objective;
  if (a.cruise != "hold" && a.cruise != "grid") {
    bad_argument("cruise", "'hold' or 'grid'", "'" + a.cruise + "'");
  }
  e.cruise_as_hold = a.cruise == "hold";
  e.threads = a.threads;
  if (train.train.pneumatic_brake_N > 0.0 && *objective == dp::Objective::Net) {
    // As the program: the DP's regeneration credit does not split the brake yet.
    bad_argument("objective", "traction for a train with a pneumatic brake (" + train.source + ")",
                 "net");
  }
  return e;
}

void check_range(const std::string& field, double value, double min, double max,
                 const std::string& expected) {
  if (!(value >= min && value <= max) || !std::isfinite(value))
    bad_argument(field, expected, data::format_number(value));
}

void check_count(const std::string& field, long long value, long long min, long long max,
                 const std::string& expected) {
  if (value < min || value > max) bad_argument(field, expected, std::to_string(value));
}

int whole_seconds(const std::string& field, double value) {
  if (value != std::floor(value) || std::fabs(value) > 1e9)
    bad_argument(field, "whole seconds", data::format_number(value));
  return static_cast<int>(value);
}

void check_fleet_train(const PyTrain& train) {
  if (train.train.has_efficiency_maps())
    bad_argument("train", "a train with constant efficiencies for the fleet models",
                 "'" + train.train.name + "'");
}

void bind_common(py::module_& m) {
  py::enum_<dp::Termination>(m, "Termination",
                             "How a solve ended: CONVERGENCE (meets every target), NO_CONVERGENCE "
                             "(a single-train run that arrives but misses its time; a fleet "
                             "search stopped by its budget, with its proven gap), FAILURE (no "
                             "result: misses its stop, or no timetable the model solved).")
      .value("CONVERGENCE", dp::Termination::CONVERGENCE)
      .value("NO_CONVERGENCE", dp::Termination::NO_CONVERGENCE)
      .value("FAILURE", dp::Termination::FAILURE);

  py::class_<PySummary>(m, "Summary",
                        "How a solve ended: termination, one-line brief_report, full_report "
                        "(problem, search, timing, result, warnings; kJ, s, km/h), warnings.")
      .def_readonly("termination", &PySummary::termination)
      .def_readonly("brief_report", &PySummary::brief_report)
      .def_readonly("full_report", &PySummary::full_report)
      .def_readonly("warnings", &PySummary::warnings)
      .def_property_readonly(
          "is_solution_usable", &PySummary::is_solution_usable,
          "Whether the result may be used, as the library's summary says (as Ceres): never for "
          "FAILURE; for NO_CONVERGENCE when the solver stopped on a budget with a result that "
          "keeps every constraint (a fleet search, with its proven gap), not when it means a "
          "run that misses its running time (single-train solves).")
      .def("__repr__", [](const PySummary& s) { return s.brief_report; });

  // ecorail.SolveError: a RuntimeError that carries the flagged result.
  py::dict scope;
  scope["__builtins__"] = py::module_::import("builtins");
  py::exec(R"(
class SolveError(RuntimeError):
    """A result that misses its stop, its running time or a timing window.

    It is never returned as a result; .result holds it (flagged: its summary says how it
    ended) for inspection."""
    def __init__(self, message, result=None):
        super().__init__(message)
        self.result = result
)",
           scope);
  py::object solve_error = scope["SolveError"];
  solve_error.attr("__module__") = "ecorail";
  m.attr("SolveError") = solve_error;

  // Every C++ exception the library throws becomes a Python one; bad input is ValueError.
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const data::InputError& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    } catch (const InvalidOptions& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    } catch (const policy::LadderTimeError& e) {
      PyErr_SetString(PyExc_ValueError, (std::string("time_s/ladder_s: ") + e.what()).c_str());
    } catch (const dp::InfeasibleTimeError& e) {
      std::string text = e.what();
      if (!e.subject().empty()) {
        text = dp::format_text(
            "time_s: expected at least the minimum running time of %.2f s for %s; got %.2f s",
            e.minimum_s(), e.subject().c_str(), e.requested_s());
      }
      PyErr_SetString(PyExc_ValueError, text.c_str());
    } catch (const dp::TimeRequestError& e) {
      PyErr_SetString(PyExc_ValueError, (std::string("time_s: ") + e.what()).c_str());
    } catch (const dp::ResourceLimitError& e) {
      PyErr_SetString(PyExc_ValueError, (std::string("ds_m/dv_kmh: ") + e.what()).c_str());
    } catch (const dp::DwellError& e) {
      PyErr_SetString(PyExc_ValueError, (std::string("dwell: ") + e.what()).c_str());
    } catch (const policy::PolicyFormatError& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    } catch (const policy::PolicyMismatchError& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    } catch (const recovery::DelayInputError& e) {
      // The argument it names, as the keyword argument is spelled.
      const std::string& f = e.field();
      const std::string field = f == "train"           ? "train_number"
                                : f == "delay"         ? "delay_s"
                                : f == "frontier-span" ? "frontier_span_s"
                                                       : f;
      PyErr_SetString(PyExc_ValueError, (field + ": expected " + e.what()).c_str());
    } catch (const std::invalid_argument& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    } catch (const std::bad_alloc&) {
      PyErr_SetString(PyExc_MemoryError, "out of memory");
    } catch (const Cancelled&) {
      PyErr_SetString(PyExc_KeyboardInterrupt, "");
    }
    // Anything else is left to pybind11's own translators (std::exception: RuntimeError).
  });
}

}  // namespace ecorail::python
