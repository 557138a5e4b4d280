// Fitting a traction or braking envelope to (speed, force) points, e.g. a digitised
// manufacturer's curve. Two forms: the piecewise form of the reference train (a constant force
// up to a breakpoint, then a polynomial of chosen degree continuous there, the breakpoint
// itself fitted), and the constant-power form F = min(Fmax, P / v). Both are least-squares fits
// by Ceres, started from a profile search over the breakpoint (piecewise) or from the data
// (constant power); standard errors come from the covariance scaled by the residual variance,
// and the ascending-power coefficients written to train files carry errors propagated from the
// fitted ones. AIC and BIC compare the forms; the lower BIC is reported as the better fit.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "dp/termination.hpp"
#include "physics/force_envelope.hpp"
#include "physics/train.hpp"

namespace ecorail::fitting {

enum class EnvelopeKind { Traction, Braking };
enum class EnvelopeForm { Piecewise, ConstantPower };

struct EnvelopePoint {
  double speed_kmh = 0.0;
  double force_kN = 0.0;
  int source_row = 0;
};

// Reads a CSV with columns speed_kmh and force_kN (InputError naming file, row and field for a
// missing column, a non-number or a negative value).
std::vector<EnvelopePoint> read_envelope_points(const std::filesystem::path& path);
std::vector<EnvelopePoint> parse_envelope_points(std::string_view text, const std::string& label);

struct EnvelopeFitOptions {
  int degree = 3;  // degree of the polynomial above the breakpoint, 1 to 6
  std::string label = "<points>";
  // False with what was expected (the degree's range) when an option is out of range.
  bool IsValid(std::string* error) const;
};

struct FormFit {
  EnvelopeForm form = EnvelopeForm::Piecewise;
  double force_max_kN = 0.0;  // the constant part
  double force_max_kN_se = 0.0;
  double breakpoint_kmh = 0.0;  // end of the constant part (P / Fmax for constant power)
  double breakpoint_kmh_se = 0.0;
  // Piecewise: F(v) = sum coeffs_kN[k] v^k for v above the breakpoint (v in km/h), and the same
  // polynomial as F = Fmax + sum local_kN[k-1] (v - breakpoint)^k.
  std::vector<double> coeffs_kN, coeffs_kN_se;
  std::vector<double> local_kN, local_kN_se;
  // Constant power.
  double power_kW = 0.0;
  double power_kW_se = 0.0;
  int parameters = 0;
  double rss_kN2 = 0.0;
  double rms_kN = 0.0;
  double max_abs_kN = 0.0;
  double aic = 0.0;
  double bic = 0.0;
  dp::Termination termination = dp::Termination::FAILURE;  // of the Ceres fit
  bool converged() const { return termination == dp::Termination::CONVERGENCE; }
  std::vector<double> fitted_kN;  // at each point
  double force_kN(double v_kmh) const;
};

struct EnvelopeFitResult {
  std::vector<EnvelopePoint> points;
  int degree = 3;
  FormFit piecewise;
  FormFit power;
  EnvelopeForm better = EnvelopeForm::Piecewise;  // lower BIC
  const FormFit& form(EnvelopeForm f) const {
    return f == EnvelopeForm::Piecewise ? piecewise : power;
  }
  std::string report(EnvelopeKind kind) const;
};

EnvelopeFitResult fit_envelope(const std::vector<EnvelopePoint>& points,
                               const EnvelopeFitOptions& options);

// The fitted form as an engine envelope, the last piece running to top_kmh.
physics::ForceEnvelope to_force_envelope(const FormFit& fit, double top_kmh);
// The base train with a fitted envelope of the kind given in place of its own, reaching the
// higher of the train's maximum speed and the fastest point (what `fit-envelope --out` writes).
physics::Train train_with_envelope(const physics::Train& base,
                                   const std::vector<EnvelopePoint>& points, const FormFit& fit,
                                   EnvelopeKind kind);

std::string_view form_name(EnvelopeForm f);
std::string_view kind_name(EnvelopeKind k);

}  // namespace ecorail::fitting
