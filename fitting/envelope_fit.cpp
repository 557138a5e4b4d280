#include "fitting/envelope_fit.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <stdexcept>

#include <ceres/ceres.h>
#include <Eigen/Dense>

#include "base/format_text.hpp"
#include "data/csv_reader.hpp"
#include "data/input_error.hpp"
#include "data/plausibility.hpp"
#include "fitting/formulation.hpp"
#include "physics/units.hpp"

namespace ecorail::fitting {

std::string_view form_name(EnvelopeForm f) {
  return f == EnvelopeForm::Piecewise ? "piecewise" : "constant_power";
}
std::string_view kind_name(EnvelopeKind k) {
  return k == EnvelopeKind::Traction ? "traction" : "braking";
}

// ---- points --------------------------------------------------------------------------------

std::vector<EnvelopePoint> parse_envelope_points(std::string_view text, const std::string& label) {
  const data::CsvTable t = data::CsvTable::parse(text, label);
  auto find = [&](std::initializer_list<const char*> names) -> std::optional<std::size_t> {
    for (const char* n : names) {
      for (std::size_t i = 0; i < t.header().size(); ++i) {
        std::string h = t.header()[i];
        std::transform(h.begin(), h.end(), h.begin(),
                       [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
        std::string want = n;
        std::transform(want.begin(), want.end(), want.begin(),
                       [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
        if (h == want) return i;
      }
    }
    return std::nullopt;
  };
  const auto v = find({"speed_kmh", "v_kmh"});
  const auto f = find({"force_kN", "F_kN"});
  if (!v) t.column("speed_kmh");  // throws the InputError naming the missing column
  if (!f) t.column("force_kN");
  std::vector<EnvelopePoint> pts;
  for (const auto& r : t.rows()) {
    EnvelopePoint p;
    p.source_row = r.row;
    p.speed_kmh = t.number(r, *v);
    p.force_kN = t.number(r, *f);
    if (p.speed_kmh < 0.0) {
      throw data::InputError(label, r.row, t.header()[*v],
                             "a speed of at least 0 km/h; got " + t.text(r, *v));
    }
    if (p.force_kN < 0.0) {
      throw data::InputError(label, r.row, t.header()[*f],
                             "a force of at least 0 kN; got " + t.text(r, *f));
    }
    // Plausibility ranges (data/plausibility.hpp): 1e300 km/h once aborted inside Ceres.
    if (p.speed_kmh > data::plausible::kMaxTrainSpeed_kmh) {
      throw data::InputError(label, r.row, t.header()[*v],
                             "a speed of at most " +
                                 data::format_number(data::plausible::kMaxTrainSpeed_kmh) +
                                 " km/h (plausibility range); got " + t.text(r, *v));
    }
    if (p.force_kN > data::plausible::kMaxForce_kN) {
      throw data::InputError(label, r.row, t.header()[*f],
                             "a force of at most " +
                                 data::format_number(data::plausible::kMaxForce_kN) +
                                 " kN (plausibility range); got " + t.text(r, *f));
    }
    pts.push_back(p);
  }
  return pts;
}

std::vector<EnvelopePoint> read_envelope_points(const std::filesystem::path& path) {
  return parse_envelope_points(data::read_text_file(path), path.string());
}

// ---- models --------------------------------------------------------------------------------

namespace {

// F = F0 for v <= vb, F0 + sum_k c_k (v - vb)^k above; x = [F0, vb, c_1 .. c_d].
double piecewise_value(const double* x, int degree, double v, double* grad) {
  const double d = v - x[1];
  if (grad != nullptr) std::fill(grad, grad + 2 + degree, 0.0);
  if (grad != nullptr) grad[0] = 1.0;
  if (d <= 0.0) return x[0];
  double f = x[0];
  double pw = 1.0;  // d^(k-1)
  double slope = 0.0;
  for (int k = 1; k <= degree; ++k) {
    slope += k * x[1 + k] * pw;
    pw *= d;
    f += x[1 + k] * pw;
    if (grad != nullptr) grad[1 + k] = pw;
  }
  if (grad != nullptr) grad[1] = -slope;
  return f;
}

class PiecewiseCost final : public ceres::CostFunction {
 public:
  PiecewiseCost(double v, double f, int degree) : v_(v), f_(f), degree_(degree) {
    set_num_residuals(1);
    mutable_parameter_block_sizes()->push_back(2 + degree);
  }
  bool Evaluate(double const* const* x, double* r, double** jac) const override {
    double g[16];
    r[0] = piecewise_value(x[0], degree_, v_, g) - f_;
    if (jac != nullptr && jac[0] != nullptr) std::copy(g, g + 2 + degree_, jac[0]);
    return true;
  }

 private:
  double v_, f_;
  int degree_;
};

// F = min(Fmax, P / v), v in m/s; x = [Fmax (kN), P (kW)].
double power_value(const double* x, double v_kmh, double* grad) {
  const double v = units::kmh_to_ms(v_kmh);
  if (x[0] * v <= x[1]) {
    if (grad != nullptr) {
      grad[0] = 1.0;
      grad[1] = 0.0;
    }
    return x[0];
  }
  if (grad != nullptr) {
    grad[0] = 0.0;
    grad[1] = 1.0 / v;
  }
  return x[1] / v;
}

class PowerCost final : public ceres::SizedCostFunction<1, 2> {
 public:
  PowerCost(double v, double f) : v_(v), f_(f) {}
  bool Evaluate(double const* const* x, double* r, double** jac) const override {
    double g[2];
    r[0] = power_value(x[0], v_, g) - f_;
    if (jac != nullptr && jac[0] != nullptr) std::copy(g, g + 2, jac[0]);
    return true;
  }

 private:
  double v_, f_;
};

struct Solved {
  std::vector<double> x;
  Eigen::MatrixXd cov;
  dp::Termination termination = dp::Termination::FAILURE;
  double rss = 0.0;
};

// Least squares on the residual blocks already in problem; covariance scaled by RSS / (n - p).
Solved solve_and_cov(ceres::Problem& problem, std::vector<double>& x, int n) {
  ceres::Solver::Options o;
  o.linear_solver_type = ceres::DENSE_QR;
  o.max_num_iterations = 200;
  o.function_tolerance = 1e-12;
  o.parameter_tolerance = 1e-12;
  o.gradient_tolerance = 1e-14;
  o.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(o, &problem, &summary);
  Solved s;
  s.termination = termination_of_ceres(summary.termination_type);
  s.rss = 2.0 * summary.final_cost;
  const int p = static_cast<int>(x.size());
  ceres::Covariance::Options co;
  co.algorithm_type = ceres::DENSE_SVD;
  co.null_space_rank = -1;  // a kink can make the breakpoint column tiny; never fail outright
  ceres::Covariance cov(co);
  s.cov = Eigen::MatrixXd::Constant(p, p, std::nan(""));
  std::vector<std::pair<const double*, const double*>> blocks = {{x.data(), x.data()}};
  if (cov.Compute(blocks, &problem)) {
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> c(p, p);
    cov.GetCovarianceBlock(x.data(), x.data(), c.data());
    const double s2 = n > p ? s.rss / (n - p) : std::nan("");
    s.cov = c * s2;
  }
  s.x = x;
  return s;
}

void finish(FormFit& fit, const std::vector<EnvelopePoint>& pts) {
  const double n = static_cast<double>(pts.size());
  fit.rss_kN2 = 0.0;
  fit.max_abs_kN = 0.0;
  fit.fitted_kN.clear();
  for (const auto& p : pts) {
    const double f = fit.force_kN(p.speed_kmh);
    fit.fitted_kN.push_back(f);
    fit.rss_kN2 += (f - p.force_kN) * (f - p.force_kN);
    fit.max_abs_kN = std::max(fit.max_abs_kN, std::abs(f - p.force_kN));
  }
  fit.rms_kN = std::sqrt(fit.rss_kN2 / n);
  const double k = fit.parameters + 1;  // + the noise variance
  const double ll = n * std::log(std::max(fit.rss_kN2, 1e-300) / n);
  fit.aic = ll + 2.0 * k;
  fit.bic = ll + k * std::log(n);
}

double binomial(int n, int k) {
  double b = 1.0;
  for (int i = 1; i <= k; ++i) b = b * (n - k + i) / i;
  return b;
}

FormFit fit_piecewise(const std::vector<EnvelopePoint>& pts, int degree) {
  const int n = static_cast<int>(pts.size());
  std::vector<double> speeds;
  for (const auto& p : pts) speeds.push_back(p.speed_kmh);
  std::sort(speeds.begin(), speeds.end());
  speeds.erase(std::unique(speeds.begin(), speeds.end()), speeds.end());
  // The breakpoint leaves at least two speeds below and degree + 1 above it.
  const double lo = speeds[1];
  const double hi = speeds[speeds.size() - static_cast<std::size_t>(degree) - 2];

  // Profile search: for a fixed breakpoint the model is linear in F0 and c_k.
  double best_rss = std::numeric_limits<double>::infinity();
  std::vector<double> best;
  const int steps = std::max(1, static_cast<int>(std::ceil((hi - lo) / 0.05)));
  for (int i = 0; i <= steps; ++i) {
    const double vb = lo + (hi - lo) * i / steps;
    Eigen::MatrixXd X(n, degree + 1);
    Eigen::VectorXd y(n);
    for (int r = 0; r < n; ++r) {
      const double d = std::max(0.0, pts[static_cast<std::size_t>(r)].speed_kmh - vb);
      double pw = 1.0;
      for (int c = 0; c <= degree; ++c) {
        X(r, c) = pw;
        pw *= d;
      }
      y(r) = pts[static_cast<std::size_t>(r)].force_kN;
    }
    const Eigen::VectorXd beta = X.colPivHouseholderQr().solve(y);
    const double rss = (X * beta - y).squaredNorm();
    if (rss < best_rss) {
      best_rss = rss;
      best.assign({beta(0), vb});
      for (int c = 1; c <= degree; ++c) best.push_back(beta(c));
    }
  }

  // No finite least-squares fit at any breakpoint: never hand Ceres an empty parameter block.
  if (best.empty()) throw std::invalid_argument("envelope fit: no finite fit at any breakpoint");
  std::vector<double> x = best;
  ceres::Problem problem;
  for (const auto& p : pts) {
    problem.AddResidualBlock(new PiecewiseCost(p.speed_kmh, p.force_kN, degree), nullptr, x.data());
  }
  problem.SetParameterLowerBound(x.data(), 1, lo);
  problem.SetParameterUpperBound(x.data(), 1, hi);
  Solved s = solve_and_cov(problem, x, n);

  FormFit fit;
  fit.form = EnvelopeForm::Piecewise;
  fit.termination = s.termination;
  fit.parameters = 2 + degree;
  fit.force_max_kN = s.x[0];
  fit.force_max_kN_se = std::sqrt(s.cov(0, 0));
  fit.breakpoint_kmh = s.x[1];
  fit.breakpoint_kmh_se = std::sqrt(s.cov(1, 1));
  for (int k = 1; k <= degree; ++k) {
    fit.local_kN.push_back(s.x[static_cast<std::size_t>(1 + k)]);
    fit.local_kN_se.push_back(std::sqrt(s.cov(1 + k, 1 + k)));
  }
  // Ascending powers of v: a_j = sum_{k>=j} ct_k C(k, j) (-vb)^(k-j), ct_0 = F0, ct_k = c_k.
  const double vb = s.x[1];
  std::vector<double> ct = {s.x[0]};
  for (int k = 1; k <= degree; ++k) ct.push_back(s.x[static_cast<std::size_t>(1 + k)]);
  Eigen::MatrixXd G = Eigen::MatrixXd::Zero(degree + 1, 2 + degree);  // d a_j / d x
  for (int j = 0; j <= degree; ++j) {
    double a = 0.0;
    for (int k = j; k <= degree; ++k) {
      const double b = binomial(k, j);
      const double mpow = std::pow(-vb, k - j);
      a += ct[static_cast<std::size_t>(k)] * b * mpow;
      G(j, k == 0 ? 0 : 1 + k) += b * mpow;
      if (k > j) {
        G(j, 1) += ct[static_cast<std::size_t>(k)] * b * (k - j) * std::pow(-vb, k - j - 1) * -1.0;
      }
    }
    fit.coeffs_kN.push_back(a);
  }
  const Eigen::MatrixXd cov_a = G * s.cov * G.transpose();
  for (int j = 0; j <= degree; ++j) fit.coeffs_kN_se.push_back(std::sqrt(cov_a(j, j)));
  finish(fit, pts);
  return fit;
}

FormFit fit_power(const std::vector<EnvelopePoint>& pts) {
  const int n = static_cast<int>(pts.size());
  std::vector<EnvelopePoint> sorted = pts;
  std::sort(sorted.begin(), sorted.end(),
            [](const auto& a, const auto& b) { return a.speed_kmh < b.speed_kmh; });
  // Start: Fmax from the slowest third, P from the fastest third.
  std::vector<double> low, high;
  for (std::size_t i = 0; i < sorted.size(); ++i) {
    if (3 * i < sorted.size()) low.push_back(sorted[i].force_kN);
    if (3 * i >= 2 * sorted.size()) {
      high.push_back(sorted[i].force_kN * units::kmh_to_ms(sorted[i].speed_kmh));
    }
  }
  auto med = [](std::vector<double> v) {
    std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
    return v[v.size() / 2];
  };
  std::vector<double> x = {std::max(med(low), 1e-3), std::max(med(high), 1e-3)};
  ceres::Problem problem;
  for (const auto& p : pts) {
    problem.AddResidualBlock(new PowerCost(p.speed_kmh, p.force_kN), nullptr, x.data());
  }
  problem.SetParameterLowerBound(x.data(), 0, 1e-6);
  problem.SetParameterLowerBound(x.data(), 1, 1e-6);
  Solved s = solve_and_cov(problem, x, n);
  FormFit fit;
  fit.form = EnvelopeForm::ConstantPower;
  fit.termination = s.termination;
  fit.parameters = 2;
  fit.force_max_kN = s.x[0];
  fit.force_max_kN_se = std::sqrt(s.cov(0, 0));
  fit.power_kW = s.x[1];
  fit.power_kW_se = std::sqrt(s.cov(1, 1));
  fit.breakpoint_kmh = units::ms_to_kmh(s.x[1] / s.x[0]);
  const Eigen::Vector2d g(-units::kKmhPerMs * s.x[1] / (s.x[0] * s.x[0]),
                          units::kKmhPerMs / s.x[0]);
  fit.breakpoint_kmh_se = std::sqrt(g.dot(s.cov * g));
  finish(fit, pts);
  return fit;
}

}  // namespace

double FormFit::force_kN(double v_kmh) const {
  if (form == EnvelopeForm::ConstantPower) {
    const double x[2] = {force_max_kN, power_kW};
    return power_value(x, v_kmh, nullptr);
  }
  std::vector<double> x = {force_max_kN, breakpoint_kmh};
  x.insert(x.end(), local_kN.begin(), local_kN.end());
  return piecewise_value(x.data(), static_cast<int>(local_kN.size()), v_kmh, nullptr);
}

bool EnvelopeFitOptions::IsValid(std::string* error) const {
  if (degree < 1 || degree > 6) {
    if (error) *error = "a polynomial degree from 1 to 6; got " + std::to_string(degree);
    return false;
  }
  return true;
}

EnvelopeFitResult fit_envelope(const std::vector<EnvelopePoint>& points,
                               const EnvelopeFitOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw data::InputError(options.label, 0, "--degree", why);
  std::map<double, int> distinct;
  for (const auto& p : points) ++distinct[p.speed_kmh];
  const std::size_t need = static_cast<std::size_t>(options.degree) + 4;
  if (distinct.size() < need) {
    throw data::InputError(options.label, 0, "",
                           "at least " + std::to_string(need) +
                               " distinct speeds to fit a constant part, a breakpoint and a "
                               "polynomial of degree " +
                               std::to_string(options.degree) + "; got " +
                               std::to_string(distinct.size()));
  }
  EnvelopeFitResult r;
  r.points = points;
  r.degree = options.degree;
  r.piecewise = fit_piecewise(points, options.degree);
  r.power = fit_power(points);
  r.better = r.power.bic < r.piecewise.bic ? EnvelopeForm::ConstantPower : EnvelopeForm::Piecewise;
  return r;
}

physics::Train train_with_envelope(const physics::Train& base,
                                   const std::vector<EnvelopePoint>& points, const FormFit& fit,
                                   EnvelopeKind kind) {
  physics::Train t = base;
  double top_kmh = units::ms_to_kmh(base.max_speed_ms);
  for (const auto& p : points) top_kmh = std::max(top_kmh, p.speed_kmh);
  const physics::ForceEnvelope env = to_force_envelope(fit, top_kmh);
  if (kind == EnvelopeKind::Traction) {
    t.traction = env;
  } else {
    t.braking = env;
  }
  return t;
}

physics::ForceEnvelope to_force_envelope(const FormFit& fit, double top_kmh) {
  if (fit.form == EnvelopeForm::ConstantPower) {
    return physics::ForceEnvelope::piecewise({{0.0, std::max(top_kmh, 1.0), {fit.force_max_kN}}},
                                             fit.power_kW);
  }
  const double top = std::max(top_kmh, fit.breakpoint_kmh + 1.0);
  return physics::ForceEnvelope::piecewise(
      {{0.0, fit.breakpoint_kmh, {fit.force_max_kN}}, {fit.breakpoint_kmh, top, fit.coeffs_kN}});
}

std::string EnvelopeFitResult::report(EnvelopeKind kind) const {
  std::string out = "\nEnvelope fit (" + std::string(kind_name(kind)) + ", " +
                    std::to_string(points.size()) + " points)\n";
  auto pm = [](double v, double se) {
    return format_text("%.6g", v) + " +- " + format_text("%.2g", se);
  };
  out += "\npiecewise: constant up to the breakpoint, then a degree-" + std::to_string(degree) +
         " polynomial continuous there\n";
  out += "  constant force      " + pm(piecewise.force_max_kN, piecewise.force_max_kN_se) + " kN\n";
  out += "  breakpoint          " + pm(piecewise.breakpoint_kmh, piecewise.breakpoint_kmh_se) +
         " km/h\n";
  for (std::size_t j = 0; j < piecewise.coeffs_kN.size(); ++j) {
    out += "  coeff v^" + std::to_string(j) + "          " +
           pm(piecewise.coeffs_kN[j], piecewise.coeffs_kN_se[j]) +
           (j == 0 ? std::string(" kN") : " kN/(km/h)^" + std::to_string(j)) + "\n";
  }
  out += "  rms " + format_text("%.4g", piecewise.rms_kN) + " kN, max |residual| " +
         format_text("%.4g", piecewise.max_abs_kN) + " kN, AIC " +
         format_text("%.2f", piecewise.aic) + ", BIC " + format_text("%.2f", piecewise.bic) +
         (piecewise.converged() ? "" : " (not converged)") + "\n";
  out += "\nconstant power: F = min(Fmax, P / v)\n";
  out += "  Fmax                " + pm(power.force_max_kN, power.force_max_kN_se) + " kN\n";
  out += "  P                   " + pm(power.power_kW, power.power_kW_se) + " kW\n";
  out += "  breakpoint P/Fmax   " + pm(power.breakpoint_kmh, power.breakpoint_kmh_se) + " km/h\n";
  out += "  rms " + format_text("%.4g", power.rms_kN) + " kN, max |residual| " +
         format_text("%.4g", power.max_abs_kN) + " kN, AIC " + format_text("%.2f", power.aic) +
         ", BIC " + format_text("%.2f", power.bic) + (power.converged() ? "" : " (not converged)") +
         "\n";
  out += "\nbetter fit (lower BIC): " + std::string(form_name(better)) + " (BIC difference " +
         format_text("%.1f", std::abs(piecewise.bic - power.bic)) + ")\n";
  return out;
}

}  // namespace ecorail::fitting
