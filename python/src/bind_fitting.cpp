// ecorail.fit_envelope and ecorail.calibrate: the Ceres fits behind `ecorail fit-envelope` and
// `ecorail calibrate`, with to_dict() equal to their --json documents (fitting/fit_json.hpp).
#include <algorithm>

#include "data/train_io.hpp"
#include "dp/threads.hpp"
#include "fitting/calibration.hpp"
#include "fitting/envelope_fit.hpp"
#include "fitting/fit_json.hpp"
#include "fitting/log_reader.hpp"
#include "python/src/common.hpp"

namespace ecorail::python {

namespace {

struct PyEnvelopeFit {
  nlohmann::json report;
  std::string report_text;
  std::string form;
  PyTrain train;  // the base train with the fitted envelope
};

struct PyCalibration {
  nlohmann::json report;
  PySummary summary;
  std::string method;
  PyTrain train;  // the base train with the written estimate
};

PyEnvelopeFit fit_envelope_py(const py::object& points_path, const std::string& kind_name,
                              const py::object& train, const std::string& form_name, int degree) {
  using namespace fitting;
  if (kind_name != "traction" && kind_name != "braking") {
    bad_argument("kind", "'traction' or 'braking'", "'" + kind_name + "'");
  }
  if (form_name != "best" && form_name != "piecewise" && form_name != "power") {
    bad_argument("form", "'best', 'piecewise' or 'power'", "'" + form_name + "'");
  }
  if (degree < 0)
    bad_argument("degree", "0 (default) or a polynomial degree >= 1", std::to_string(degree));
  const EnvelopeKind kind = kind_name == "braking" ? EnvelopeKind::Braking : EnvelopeKind::Traction;
  const PyTrain base =
      train.is_none() ? PyTrain{data::default_train(), "embedded"} : py::cast<PyTrain>(train);
  const std::string path = fspath(points_path);
  const std::vector<EnvelopePoint> points = read_envelope_points(path);
  EnvelopeFitOptions options;
  options.degree = degree > 0 ? degree : (kind == EnvelopeKind::Traction ? 3 : 2);
  options.label = path;
  EnvelopeFitResult result;
  {
    py::gil_scoped_release release;
    result = fit_envelope(points, options);
  }
  const EnvelopeForm written = form_name == "piecewise" ? EnvelopeForm::Piecewise
                               : form_name == "power"   ? EnvelopeForm::ConstantPower
                                                        : result.better;
  const FormFit& fit = result.form(written);
  if (!fit.converged()) {
    throw std::runtime_error(std::string(fitting::form_name(written)) + " fit did not converge");
  }
  PyEnvelopeFit out;
  out.report = envelope_fit_to_json(result, kind, written);
  out.report_text = result.report(kind);
  out.form = std::string(fitting::form_name(written));
  out.train = {train_with_envelope(base.train, points, fit, kind), base.source};
  return out;
}

PyCalibration calibrate_py(const std::vector<py::object>& log_paths, const py::object& train,
                           const std::string& method, const std::vector<std::string>& fix,
                           bool fit_mass, bool fit_traction_scale,
                           const std::string& gradient_scale, const std::string& loss,
                           double loss_scale, int segment_rows, int max_iterations, int threads,
                           bool accel_limits, const py::object& progress) {
  using namespace fitting;
  if (log_paths.empty()) bad_argument("logs", "at least one per-second log", "none");
  CalibrationOptions o;
  if (method != "equation" && method != "output" && method != "both") {
    bad_argument("method", "'equation', 'output' or 'both'", "'" + method + "'");
  }
  o.method = method == "equation" ? Method::EquationError
             : method == "output" ? Method::OutputError
                                  : Method::Both;
  if (loss != "cauchy" && loss != "huber" && loss != "none") {
    bad_argument("loss", "'cauchy', 'huber' or 'none'", "'" + loss + "'");
  }
  o.loss = loss == "huber" ? LossKind::Huber : loss == "none" ? LossKind::None : LossKind::Cauchy;
  if (!(loss_scale > 0.0))
    bad_argument("loss_scale", "a loss scale above 0 (sigmas)", std::to_string(loss_scale));
  o.loss_scale = loss_scale;
  for (const auto& name : fix) {
    const auto p = param_from_name(name);
    if (!p) {
      ParamFlags all{};
      all.fill(true);
      bad_argument("fix", "one of " + param_list(all), "'" + name + "'");
    }
    o.fixed[static_cast<std::size_t>(*p)] = true;
  }
  o.fit_mass = fit_mass;
  o.fit_traction_scale = fit_traction_scale;
  if (gradient_scale != "auto" && gradient_scale != "fit" && gradient_scale != "fixed") {
    bad_argument("gradient_scale", "'auto', 'fit' or 'fixed'", "'" + gradient_scale + "'");
  }
  o.gradient_scale = gradient_scale == "fit"     ? GradientScaleMode::Fit
                     : gradient_scale == "fixed" ? GradientScaleMode::Fixed
                                                 : GradientScaleMode::Auto;
  if (segment_rows < 1)
    bad_argument("segment_rows", "at least 1 row per segment", std::to_string(segment_rows));
  o.output_error.segment_rows = segment_rows;
  if (max_iterations < 1)
    bad_argument("max_iterations", "at least 1 iteration", std::to_string(max_iterations));
  o.max_iterations = max_iterations;
  if (threads < 0 || threads > dp::kMaxThreads) {
    bad_argument("threads", "1 to " + std::to_string(dp::kMaxThreads) + " threads",
                 std::to_string(threads));
  }
  o.num_threads = std::max(1, threads);
  o.apply_accel_limits = accel_limits;
  const PyTrain base =
      train.is_none() ? PyTrain{data::default_train(), "embedded"} : py::cast<PyTrain>(train);
  std::vector<Log> logs;
  for (const auto& path : log_paths) logs.push_back(read_log(fspath(path)));
  Interruptible guard(progress);
  o.progress = guard.callback();
  const Summary s = guard.run([&] { return calibrate(logs, base.train, o); });
  PyCalibration out;
  out.report = calibration_to_json(s);
  const FormulationSummary* converged = nullptr;
  try {
    converged = &s.converged_primary();
  } catch (const NotConvergedError& e) {
    throw std::runtime_error(std::string(e.what()) + " (raise max_iterations, now " +
                             std::to_string(max_iterations) + ", or add logs)");
  }
  out.summary.termination = dp::Termination::CONVERGENCE;
  out.summary.brief_report = s.BriefReport();
  out.summary.full_report = s.FullReport();
  out.summary.warnings = s.notes;
  out.method = std::string(method_name(converged->method));
  out.train = {calibrated_train(base.train, *converged), base.source};
  return out;
}

}  // namespace

void bind_fitting(py::module_& m) {
  py::class_<PyEnvelopeFit>(m, "EnvelopeFit",
                            "A fitted traction or braking envelope (piecewise and constant-power "
                            "forms, standard errors, AIC/BIC).")
      .def(
          "to_dict", [](const PyEnvelopeFit& f) { return to_python(f.report); },
          "The document `ecorail fit-envelope --json` writes.")
      .def_readonly("report", &PyEnvelopeFit::report_text, "The printed report of both forms.")
      .def_readonly("form", &PyEnvelopeFit::form, "The form written into train.")
      .def_readonly("train", &PyEnvelopeFit::train,
                    "The base train with the fitted envelope (Train.to_toml() is the program's "
                    "--out file).");
  py::class_<PyCalibration>(m, "Calibration",
                            "A calibrated train model: Davis A, B, C, rotating-mass factor, "
                            "gradient scale (optionally mass, traction scale) with standard "
                            "errors.")
      .def(
          "to_dict", [](const PyCalibration& c) { return to_python(c.report); },
          "The document `ecorail calibrate --json` writes.")
      .def_readonly("summary", &PyCalibration::summary)
      .def_readonly("method", &PyCalibration::method, "The estimate written into train.")
      .def_readonly("train", &PyCalibration::train,
                    "The base train with the fitted values (the program's --out file as "
                    "Train.to_toml()).");

  m.def("fit_envelope", &fit_envelope_py, py::arg("points"), py::kw_only(), py::arg("kind"),
        py::arg("train") = py::none(), py::arg("form") = "best", py::arg("degree") = 0,
        "Fits a traction or braking envelope (kind) to the points of a CSV (columns speed_kmh, "
        "force_kN), as `ecorail fit-envelope`: both forms are fitted; form chooses the one "
        "written into the base train ('best': lower BIC). degree: polynomial degree above the "
        "breakpoint (0: 3 for traction, 2 for braking).");
  m.def("calibrate", &calibrate_py, py::arg("logs"), py::kw_only(), py::arg("train") = py::none(),
        py::arg("method") = "both", py::arg("fix") = std::vector<std::string>{},
        py::arg("fit_mass") = false, py::arg("fit_traction_scale") = false,
        py::arg("gradient_scale") = "auto", py::arg("loss") = "cauchy", py::arg("loss_scale") = 2.5,
        py::arg("segment_rows") = 10, py::arg("max_iterations") = 100, py::arg("threads") = 1,
        py::arg("accel_limits") = true, py::arg("progress") = py::none(),
        "Calibrates the train model from per-second logs (paths), as `ecorail calibrate`: "
        "method 'equation', 'output' or 'both'; fix holds parameters at their start; loss "
        "'cauchy', 'huber' or 'none' with loss_scale in noise standard deviations; threads for "
        "Ceres. A fit that does not converge raises RuntimeError.");
}

}  // namespace ecorail::python
