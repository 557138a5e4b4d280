// Calibration of a train model from per-second logs: estimates the Davis coefficients A, B, C,
// the rotating-mass factor and a gradient scale, optionally the mass and a traction-force scale,
// by two formulations solved with Ceres under a robust loss (equation error on the equation of
// motion, output error by multiple shooting), with bounds, standard errors from the covariance,
// residual statistics and the rows the robust loss discounted. The interface follows Ceres:
// an Options struct in, a Summary with BriefReport() and FullReport() out. Units at the edge are
// those of docs/model.md (N/kN with v in km/h, t, km/h); inside everything is SI.
#pragma once

#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "base/error.hpp"
#include "dp/progress_callback.hpp"
#include "fitting/formulation.hpp"
#include "fitting/identifiability.hpp"
#include "fitting/log_plausibility.hpp"
#include "fitting/log_prep.hpp"
#include "fitting/log_reader.hpp"
#include "fitting/output_error.hpp"
#include "fitting/parameters.hpp"
#include "physics/train.hpp"

namespace ecorail::fitting {

enum class Method { EquationError, OutputError, Both };
enum class GradientScaleMode { Auto, Fit, Fixed };  // Auto: fit when the logs show gradient

std::string_view method_name(Method m);

struct CalibrationOptions {
  Method method = Method::Both;
  LossKind loss = LossKind::Cauchy;
  double loss_scale = 2.5;        // in noise standard deviations
  double discount_weight = 0.25;  // robust weight below which a row counts as discounted
  int robust_passes = 2;
  // Parameters to hold at their starting values (davis_A ... traction_scale).
  ParamFlags fixed{};
  bool fit_mass = false;
  bool fit_traction_scale = false;
  GradientScaleMode gradient_scale = GradientScaleMode::Auto;
  double gradient_scale_start = 1.0;
  bool apply_accel_limits = true;
  OutputErrorOptions output_error;
  PrepOptions prep;
  PlausibilityOptions plausibility;  // rows no train of the model could produce are refused
  IdentifiabilityOptions identifiability;
  // Ceres iterations per pass (plain, then robust). The shipped A6 -> A7 log's output-error fit
  // needs 175 in its last pass.
  int max_iterations = 500;
  int num_threads = 1;
  // Called with ("equation-error pass" or "output-error pass", pass, passes) as the fits run.
  dp::ProgressFn progress;
  // False with one sentence naming the first field out of range; calibrate() checks it first
  // (std::invalid_argument).
  bool IsValid(std::string* error) const;
};

struct ParameterEstimate {
  double value = 0.0;
  double se = 0.0;  // NaN when fixed or the covariance failed
  double start = 0.0;
  double lower = 0.0;
  double upper = 0.0;
  bool fixed = false;
  bool at_bound = false;
};

struct FormulationSummary {
  Method method = Method::EquationError;  // EquationError or OutputError
  std::array<ParameterEstimate, kParamCount> params{};
  ParamCovariance covariance{};
  FitResult fit;
  const char* residual_unit = "";  // "m/s^2" or "m/s"
  // Level-track coasting deceleration (m/s^2, positive) of the fitted resistance at v (km/h).
  double coasting_decel_m_s2(double v_kmh, double gravity_m_s2) const;
};

struct Summary {
  std::vector<std::string> logs;  // labels
  PreparedData data;
  std::vector<FormulationSummary> results;  // in the order equation error, output error
  std::vector<std::string> notes;
  ParamFlags fitted{};  // which parameters were free
  CalibrationOptions options;
  physics::Train base;
  double total_time_s = 0.0;

  // The result written to train files: output error when it ran, else equation error.
  const FormulationSummary& primary() const;
  // primary(), for writing: throws NotConvergedError when its fit did not converge, because a
  // fit Ceres stopped early (NO_CONVERGENCE, an iteration limit) is not an estimate.
  const FormulationSummary& converged_primary() const;
  const FormulationSummary* find(Method m) const;
  std::string BriefReport() const;
  std::string FullReport() const;
};

// A calibration whose written result did not converge (see Summary::converged_primary).
class NotConvergedError : public std::runtime_error, public Error {
 public:
  explicit NotConvergedError(const std::string& what)
      : std::runtime_error(what), Error(ErrorKind::kNotConverged) {}
};

// Runs the calibration; throws data::InputError for unusable logs (physically impossible rows
// included, see log_plausibility.hpp) or unidentifiable parameters.
Summary calibrate(const std::vector<Log>& logs, const physics::Train& base,
                  const CalibrationOptions& options);

// The base train with the fitted values of a result: Davis A, B, C, rotating-mass factor, mass
// when fitted, traction envelope scaled when the traction scale was fitted (the gradient scale
// describes the log, not the train, and is not written).
physics::Train calibrated_train(const physics::Train& base, const FormulationSummary& result);

}  // namespace ecorail::fitting
