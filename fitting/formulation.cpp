#include "fitting/formulation.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>

namespace ecorail::fitting {

dp::Termination termination_of_ceres(ceres::TerminationType type) {
  switch (type) {
    case ceres::CONVERGENCE:
    case ceres::USER_SUCCESS:
      return dp::Termination::CONVERGENCE;
    case ceres::NO_CONVERGENCE:
      return dp::Termination::NO_CONVERGENCE;
    default:
      return dp::Termination::FAILURE;
  }
}

namespace {

struct PassOutcome {
  ceres::Solver::Summary summary;
};

void configure_params(ceres::Problem& problem, double* params, const FitSetup& setup) {
  std::vector<int> fixed;
  for (int p = 0; p < kParamCount; ++p) {
    if (setup.fixed[static_cast<std::size_t>(p)]) fixed.push_back(p);
  }
  if (!fixed.empty()) {
    problem.SetManifold(params, new ceres::SubsetManifold(kParamCount, fixed));
  }
  for (int p = 0; p < kParamCount; ++p) {
    if (setup.fixed[static_cast<std::size_t>(p)]) continue;
    problem.SetParameterLowerBound(params, p, setup.lower[static_cast<std::size_t>(p)]);
    problem.SetParameterUpperBound(params, p, setup.upper[static_cast<std::size_t>(p)]);
  }
}

ceres::Solver::Options solver_options(const Formulation& f, const FitSetup& setup) {
  ceres::Solver::Options o;
  o.minimizer_type = ceres::TRUST_REGION;
  o.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
  o.linear_solver_type = f.linear_solver();
  o.max_num_iterations = setup.max_iterations;
  o.function_tolerance = 1e-10;
  o.gradient_tolerance = 1e-12;
  o.parameter_tolerance = 1e-10;
  o.num_threads = setup.num_threads;
  o.logging_type = ceres::SILENT;
  return o;
}

// Reports (stage, pass, passes) at every Ceres iteration, so that a long pass keeps the
// progress line's clock moving.
class PassProgress : public ceres::IterationCallback {
 public:
  PassProgress(const FitSetup& setup, int pass, int passes)
      : setup_(setup), pass_(pass), passes_(passes) {}
  ceres::CallbackReturnType operator()(const ceres::IterationSummary&) override {
    dp::report_progress(setup_.progress, setup_.progress_stage, pass_, passes_);
    return ceres::SOLVER_CONTINUE;
  }

 private:
  const FitSetup& setup_;
  int pass_, passes_;
};

}  // namespace

FitResult run_fit(Formulation& f, const FitSetup& setup) {
  const auto start = std::chrono::steady_clock::now();
  FitResult out;
  ParamVector params = setup.initial;
  // Bounds must hold at the start.
  for (int p = 0; p < kParamCount; ++p) {
    const auto i = static_cast<std::size_t>(p);
    if (!setup.fixed[i]) params[i] = std::clamp(params[i], setup.lower[i], setup.upper[i]);
  }

  double sigma = robust_sigma(f.residuals(params), f.sigma_floor());
  std::unique_ptr<ceres::LossFunction> loss;
  std::unique_ptr<ceres::Problem> problem;
  ceres::Solver::Summary summary;
  // Without a robust loss the second pass only rescales: sigma from the residual sum of
  // squares of the least-squares solution, so the covariance is the classical one.
  const bool plain = setup.loss == LossKind::None;
  const int passes = 1 + (plain ? 1 : std::max(1, setup.robust_passes));
  int free_params = 0;
  for (bool fixed : setup.fixed) free_params += fixed ? 0 : 1;
  for (int pass = 0; pass < passes; ++pass) {
    if (pass > 0) {
      const std::vector<double> r = f.residuals(params);
      if (plain) {
        double ss = 0.0;
        for (double x : r) ss += x * x;
        const double dof = std::max(1.0, static_cast<double>(r.size()) - free_params);
        sigma = std::max(std::sqrt(ss / dof), f.sigma_floor());
      } else {
        sigma = robust_sigma(r, f.sigma_floor());
      }
    }
    loss = pass == 0 ? nullptr : make_loss(setup.loss, setup.loss_scale);
    ceres::Problem::Options po;
    po.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
    po.cost_function_ownership = ceres::TAKE_OWNERSHIP;
    po.manifold_ownership = ceres::TAKE_OWNERSHIP;
    problem = std::make_unique<ceres::Problem>(po);
    problem->AddParameterBlock(params.data(), kParamCount);
    f.add_blocks(*problem, params.data(), sigma, loss.get());
    configure_params(*problem, params.data(), setup);
    ceres::Solver::Options so = solver_options(f, setup);
    PassProgress pass_progress(setup, pass, passes);
    if (setup.progress) {
      so.callbacks.push_back(&pass_progress);
      so.update_state_every_iteration = false;
    }
    ceres::Solve(so, problem.get(), &summary);
    dp::report_progress(setup.progress, setup.progress_stage, pass + 1, passes);
    if (pass == 0) out.initial_cost = summary.initial_cost;
    out.last_pass_iterations = static_cast<int>(summary.iterations.size()) - 1;
    out.iterations += out.last_pass_iterations;
  }
  out.passes = passes;
  out.max_iterations_per_pass = setup.max_iterations;
  out.value = params;
  out.sigma = sigma;
  out.final_cost = summary.final_cost;
  out.termination = termination_of_ceres(summary.termination_type);
  out.ceres_brief = summary.BriefReport();

  // Covariance of the parameter block; residuals are already divided by sigma.
  ceres::Covariance::Options co;
  co.num_threads = setup.num_threads;
  if (f.sparse_covariance()) {
    co.algorithm_type = ceres::SPARSE_QR;
    co.sparse_linear_algebra_library_type = ceres::SUITE_SPARSE;
  } else {
    co.algorithm_type = ceres::DENSE_SVD;
  }
  ceres::Covariance cov(co);
  std::vector<std::pair<const double*, const double*>> blocks = {{params.data(), params.data()}};
  out.covariance_ok = cov.Compute(blocks, problem.get());
  if (out.covariance_ok) {
    cov.GetCovarianceBlock(params.data(), params.data(), out.covariance.data());
  } else {
    out.covariance.fill(std::nan(""));
  }

  const std::vector<double> r = f.residuals(params);
  out.residual_count = static_cast<int>(r.size());
  double ss = 0.0;
  for (double x : r) {
    ss += x * x;
    out.max_abs = std::max(out.max_abs, std::abs(x));
    if (robust_weight(setup.loss, setup.loss_scale, x / sigma) < setup.discount_weight) {
      ++out.discounted_residuals;
    }
  }
  out.rms = r.empty() ? 0.0 : std::sqrt(ss / static_cast<double>(r.size()));
  out.discounted = f.discounted_rows(params, sigma, setup);
  out.solve_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace ecorail::fitting
