// The common frame of the two calibration formulations (equation error and output error): the
// settings they share, their result, and the robust fitting loop that drives either one. The
// loop is: a plain least-squares pass from the starting values, then robust passes, each with
// the noise scale re-estimated from the median residual of the previous pass; residuals are
// divided by that scale, so the covariance Ceres computes at the end is the parameter
// covariance itself and the loss thresholds read in standard deviations. Without a robust loss
// the second pass only rescales, by the rms residual, giving the classical covariance.
#pragma once

#include <string>
#include <vector>

#include <ceres/ceres.h>

#include "dp/progress_callback.hpp"
#include "dp/termination.hpp"
#include "fitting/log_prep.hpp"
#include "fitting/motion_model.hpp"
#include "fitting/parameters.hpp"
#include "fitting/robust.hpp"

namespace ecorail::fitting {

struct FitSetup {
  const PreparedData* data = nullptr;
  ModelConstants constants;
  ParamVector initial{};
  ParamVector lower{};
  ParamVector upper{};
  ParamFlags fixed{};
  LossKind loss = LossKind::Cauchy;
  double loss_scale = 2.5;        // in noise standard deviations
  double discount_weight = 0.25;  // rows weighted less than this are reported as discounted
  int robust_passes = 2;
  int max_iterations = 500;  // per pass
  int num_threads = 1;
  // Called with (progress_stage, pass, passes) at every Ceres iteration and after each pass.
  dp::ProgressFn progress;
  const char* progress_stage = "fit";
};

struct DiscountedRow {
  int log_index = 0;
  int source_row = 0;
  double time_s = 0.0;
  double z = 0.0;       // residual in noise standard deviations
  double weight = 1.0;  // the loss function's weight of that residual
};

// A Ceres termination as the library's: CONVERGENCE (and USER_SUCCESS), NO_CONVERGENCE, or
// FAILURE (and USER_FAILURE).
dp::Termination termination_of_ceres(ceres::TerminationType type);

struct FitResult {
  ParamVector value{};
  ParamCovariance covariance{};
  bool covariance_ok = false;
  double sigma = 0.0;  // noise scale of the final pass, in the residual's unit
  int residual_count = 0;
  double rms = 0.0;  // raw residual, unit as sigma
  double max_abs = 0.0;
  int discounted_residuals = 0;
  std::vector<DiscountedRow> discounted;
  int iterations = 0;            // over all passes
  int passes = 0;                // plain pass plus robust passes
  int last_pass_iterations = 0;  // of the final pass, whose termination is reported
  int max_iterations_per_pass = 0;
  double initial_cost = 0.0;
  double final_cost = 0.0;
  // How the final pass ended, Ceres' CONVERGENCE / NO_CONVERGENCE / FAILURE (USER_SUCCESS
  // counts as CONVERGENCE, USER_FAILURE as FAILURE).
  dp::Termination termination = dp::Termination::FAILURE;
  bool converged() const { return termination == dp::Termination::CONVERGENCE; }
  std::string ceres_brief;  // Ceres' BriefReport of the final pass
  double solve_time_s = 0.0;
};

// One formulation: builds its residual blocks and evaluates raw residuals for the noise scale.
class Formulation {
 public:
  virtual ~Formulation() = default;
  // Raw residuals (unit of sigma) at params, with the formulation's own auxiliary state.
  virtual std::vector<double> residuals(const ParamVector& params) const = 0;
  // Adds every residual block to problem; params is the parameter block of kParamCount.
  virtual void add_blocks(ceres::Problem& problem, double* params, double sigma,
                          ceres::LossFunction* loss) = 0;
  virtual double sigma_floor() const = 0;
  virtual ceres::LinearSolverType linear_solver() const = 0;
  virtual bool sparse_covariance() const = 0;
  // Rows whose residuals the loss discounted, given the final residuals and scale.
  virtual std::vector<DiscountedRow> discounted_rows(const ParamVector& params, double sigma,
                                                     const FitSetup& setup) const = 0;
};

FitResult run_fit(Formulation& f, const FitSetup& setup);

}  // namespace ecorail::fitting
