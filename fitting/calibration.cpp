#include "fitting/calibration.hpp"

#include <chrono>
#include <cmath>
#include <stdexcept>

#include "data/csv_reader.hpp"
#include "data/input_error.hpp"
#include "dp/threads.hpp"
#include "fitting/equation_error.hpp"

namespace ecorail::fitting {

std::string_view method_name(Method m) {
  switch (m) {
    case Method::EquationError:
      return "equation error";
    case Method::OutputError:
      return "output error";
    case Method::Both:
      return "both";
  }
  return "?";
}

double FormulationSummary::coasting_decel_m_s2(double v_kmh, double gravity_m_s2) const {
  const double w =
      params[kDavisA].value + v_kmh * (params[kDavisB].value + v_kmh * params[kDavisC].value);
  return gravity_m_s2 * w / 1000.0 / (1.0 + params[kRotatingMassFactor].value);
}

const FormulationSummary& Summary::primary() const {
  if (const auto* oe = find(Method::OutputError)) return *oe;
  return results.at(0);
}

const FormulationSummary& Summary::converged_primary() const {
  const FormulationSummary& r = primary();
  if (!r.fit.converged()) {
    throw NotConvergedError(std::string(method_name(r.method)) + " fit ended " +
                            std::string(dp::termination_name(r.fit.termination)) + " in pass " +
                            std::to_string(r.fit.passes) + " of " + std::to_string(r.fit.passes) +
                            " after " + std::to_string(r.fit.last_pass_iterations) +
                            " of at most " + std::to_string(r.fit.max_iterations_per_pass) +
                            " iterations (" + std::to_string(r.fit.iterations) +
                            " over all passes): no calibrated train written");
  }
  return r;
}

const FormulationSummary* Summary::find(Method m) const {
  for (const auto& r : results) {
    if (r.method == m) return &r;
  }
  return nullptr;
}

namespace {

FormulationSummary summarise(Method m, const FitResult& fit, const FitSetup& setup) {
  FormulationSummary s;
  s.method = m;
  s.fit = fit;
  s.covariance = fit.covariance;
  s.residual_unit = m == Method::EquationError ? "m/s^2" : "m/s";
  for (int p = 0; p < kParamCount; ++p) {
    const auto i = static_cast<std::size_t>(p);
    ParameterEstimate& e = s.params[i];
    e.value = fit.value[i];
    e.start = setup.initial[i];
    e.lower = setup.lower[i];
    e.upper = setup.upper[i];
    e.fixed = setup.fixed[i];
    const double var = fit.covariance[i * kParamCount + i];
    e.se = (!e.fixed && fit.covariance_ok && var >= 0.0) ? std::sqrt(var) : std::nan("");
    if (!e.fixed) {
      const double tol = 1e-9 * std::max(1.0, std::abs(e.upper - e.lower));
      e.at_bound = std::abs(e.value - e.lower) < tol || std::abs(e.value - e.upper) < tol;
    }
  }
  return s;
}

}  // namespace

bool CalibrationOptions::IsValid(std::string* error) const {
  auto fail = [&](const char* why) {
    if (error) *error = why;
    return false;
  };
  if (!(loss_scale > 0.0 && std::isfinite(loss_scale))) {
    return fail("loss_scale must be a positive number of noise standard deviations");
  }
  if (!(discount_weight >= 0.0 && discount_weight <= 1.0)) {
    return fail("discount_weight must be in [0, 1]");
  }
  if (robust_passes < 1) return fail("robust_passes must be at least 1");
  if (max_iterations < 1) return fail("max_iterations must be at least 1");
  if (num_threads < 1 || num_threads > dp::kMaxThreads) {
    return fail("num_threads must be from 1 to dp::kMaxThreads");
  }
  if (output_error.segment_rows < 1) return fail("output_error.segment_rows must be at least 1");
  if (!(output_error.continuity_fraction > 0.0 &&
        std::isfinite(output_error.continuity_fraction))) {
    return fail("output_error.continuity_fraction must be a positive fraction of the noise scale");
  }
  return true;
}

Summary calibrate(const std::vector<Log>& logs, const physics::Train& base,
                  const CalibrationOptions& options) {
  const auto start_time = std::chrono::steady_clock::now();
  std::string why;
  if (!options.IsValid(&why)) throw std::invalid_argument(why);
  if (logs.empty()) throw data::InputError("", 0, "--log", "at least one log file");
  Summary s;
  s.options = options;
  s.base = base;
  for (const auto& l : logs) s.logs.push_back(l.label);
  check_logs_plausible(logs, base, options.plausibility);
  s.data = prepare_logs(logs, base, options.prep);

  ModelConstants k;
  k.gravity_m_s2 = base.gravity_m_s2;
  k.max_accel_m_s2 = base.max_accel_m_s2;
  k.max_decel_m_s2 = base.max_decel_m_s2;
  k.apply_accel_limits = options.apply_accel_limits;

  FitSetup setup;
  setup.data = &s.data;
  setup.constants = k;
  setup.initial = params_from_train(base);
  setup.initial[kGradientScale] = options.gradient_scale_start;
  setup.lower = default_lower_bounds(base);
  setup.upper = default_upper_bounds(base);
  setup.fixed = options.fixed;
  if (!options.fit_mass) setup.fixed[kMassT] = true;
  if (!options.fit_traction_scale) setup.fixed[kTractionScale] = true;
  switch (options.gradient_scale) {
    case GradientScaleMode::Fixed:
      setup.fixed[kGradientScale] = true;
      break;
    case GradientScaleMode::Fit:
      break;
    case GradientScaleMode::Auto:
      if (s.data.gradient_intervals < std::max(10, s.data.used_intervals / 20)) {
        setup.fixed[kGradientScale] = true;
        s.notes.push_back("gradient_scale held at " +
                          data::format_number(options.gradient_scale_start) + ": only " +
                          std::to_string(s.data.gradient_intervals) +
                          " usable intervals on a gradient");
      }
      break;
  }
  setup.loss = options.loss;
  setup.loss_scale = options.loss_scale;
  setup.discount_weight = options.discount_weight;
  setup.robust_passes = options.robust_passes;
  setup.max_iterations = options.max_iterations;
  setup.num_threads = options.num_threads;
  setup.progress = options.progress;
  for (int p = 0; p < kParamCount; ++p) {
    s.fitted[static_cast<std::size_t>(p)] = !setup.fixed[static_cast<std::size_t>(p)];
  }

  check_identifiable(s.data, k, setup.initial, setup.fixed, options.identifiability);

  if (options.method != Method::OutputError) {
    auto ee = make_equation_error(s.data, k);
    setup.progress_stage = "equation-error pass";
    const FitResult fit = run_fit(*ee, setup);
    s.results.push_back(summarise(Method::EquationError, fit, setup));
  }
  if (options.method != Method::EquationError) {
    FitSetup oe_setup = setup;
    oe_setup.progress_stage = "output-error pass";
    // Multiple shooting starts best from the equation-error estimate when there is one.
    if (!s.results.empty()) oe_setup.initial = s.results.back().fit.value;
    auto oe = make_output_error(s.data, k, options.output_error);
    const FitResult fit = run_fit(*oe, oe_setup);
    FormulationSummary r = summarise(Method::OutputError, fit, oe_setup);
    for (int p = 0; p < kParamCount; ++p) {
      r.params[static_cast<std::size_t>(p)].start = setup.initial[static_cast<std::size_t>(p)];
    }
    s.results.push_back(r);
  }
  for (const auto& r : s.results) {
    const std::string who = std::string(method_name(r.method));
    if (!r.fit.converged()) {
      s.notes.push_back(who + ": Ceres stopped without convergence (" +
                        std::string(dp::termination_name(r.fit.termination)) + ")");
    }
    if (!r.fit.covariance_ok) {
      s.notes.push_back(who + ": the covariance is rank deficient; standard errors unavailable");
    }
    for (int p = 0; p < kParamCount; ++p) {
      if (r.params[static_cast<std::size_t>(p)].at_bound) {
        s.notes.push_back(who + ": " + std::string(param_name(p)) +
                          " ended on a bound; its standard error describes the unconstrained "
                          "curvature only");
      }
    }
  }
  s.total_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_time).count();
  return s;
}

physics::Train calibrated_train(const physics::Train& base, const FormulationSummary& r) {
  physics::Train t = base;
  auto v = [&](Param p) { return r.params[static_cast<std::size_t>(p)].value; };
  t.davis.A = v(kDavisA);
  t.davis.B = v(kDavisB);
  t.davis.C = v(kDavisC);
  t.rotating_mass_factor = v(kRotatingMassFactor);
  t.mass_kg = v(kMassT) * 1000.0;
  const double kf = v(kTractionScale);
  if (!r.params[kTractionScale].fixed && kf != 1.0) {
    const physics::ForceEnvelope& e = base.traction;
    if (e.is_table()) {
      auto pts = e.points();
      for (auto& p : pts) p.force_kN *= kf;
      t.traction = physics::ForceEnvelope::table(pts, e.power_cap_kW() * kf);
    } else {
      auto pieces = e.pieces();
      for (auto& p : pieces) {
        for (auto& c : p.coeffs_kN) c *= kf;
      }
      t.traction = physics::ForceEnvelope::piecewise(pieces, e.power_cap_kW() * kf);
    }
  }
  if (t.name.find("(calibrated)") == std::string::npos) t.name += " (calibrated)";
  return t;
}

}  // namespace ecorail::fitting
