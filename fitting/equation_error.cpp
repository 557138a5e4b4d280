#include "fitting/equation_error.hpp"

#include <cmath>
#include <limits>

#include <Eigen/Dense>

namespace ecorail::fitting {

namespace {

// A speed error e at row r adds +e/dt to interval r-1 and -e/dt to interval r, so corrections
// c (in units of sigma) at a set S of rows change interval m to z_m + c_m - c_{m+1}. The
// discounted intervals are grouped into clusters of consecutive ones; for each cluster the
// smallest set of its rows whose least-squares corrections bring every interval they touch
// back under the discount limit is blamed. So the row between two corrupted rows is cleared
// and two adjacent corrupted rows are both named. A cluster no set explains (a glitch in the
// force rather than the speed) blames all its rows.
std::vector<bool> attribute_rows(const std::vector<double>& z, const std::vector<bool>& used,
                                 double z_limit) {
  const std::size_t m = z.size();
  std::vector<bool> flagged(m + 1, false);
  auto bad = [&](std::size_t i) { return used[i] && std::abs(z[i]) > z_limit; };
  std::size_t i = 0;
  while (i < m) {
    if (!bad(i)) {
      ++i;
      continue;
    }
    std::size_t end = i;
    while (end < m && bad(end)) ++end;  // cluster: intervals i .. end-1, rows i .. end
    const std::size_t first_row = i;
    const std::size_t rows = end - i + 1;
    bool explained = false;
    if (rows <= 12) {
      double best_cost = std::numeric_limits<double>::infinity();
      unsigned best_mask = 0;
      for (std::size_t k = 1; k <= rows && !explained; ++k) {
        for (unsigned mask = 1; mask < (1u << rows); ++mask) {
          if (static_cast<std::size_t>(__builtin_popcount(mask)) != k) continue;
          // Intervals touched: the cluster and the used neighbours of the chosen rows.
          std::vector<std::size_t> touched;
          for (std::size_t q = i; q < end; ++q) touched.push_back(q);
          std::vector<std::size_t> chosen;
          for (std::size_t b = 0; b < rows; ++b) {
            if (!(mask & (1u << b))) continue;
            const std::size_t r = first_row + b;
            chosen.push_back(r);
            if (r > 0 && used[r - 1] && (r - 1 < i || r - 1 >= end)) touched.push_back(r - 1);
            if (r < m && used[r] && (r < i || r >= end)) touched.push_back(r);
          }
          Eigen::MatrixXd M = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(touched.size()),
                                                    static_cast<Eigen::Index>(chosen.size()));
          Eigen::VectorXd zz(static_cast<Eigen::Index>(touched.size()));
          for (std::size_t t = 0; t < touched.size(); ++t) {
            const std::size_t q = touched[t];
            zz(static_cast<Eigen::Index>(t)) = z[q];
            for (std::size_t c = 0; c < chosen.size(); ++c) {
              if (chosen[c] == q)
                M(static_cast<Eigen::Index>(t), static_cast<Eigen::Index>(c)) = 1.0;
              if (chosen[c] == q + 1) {
                M(static_cast<Eigen::Index>(t), static_cast<Eigen::Index>(c)) = -1.0;
              }
            }
          }
          const Eigen::VectorXd corr = M.colPivHouseholderQr().solve(-zz);
          const Eigen::VectorXd after = zz + M * corr;
          if (after.cwiseAbs().maxCoeff() <= z_limit && after.squaredNorm() < best_cost) {
            best_cost = after.squaredNorm();
            best_mask = mask;
            explained = true;
          }
        }
      }
      for (std::size_t b = 0; b < rows && explained; ++b) {
        if (best_mask & (1u << b)) flagged[first_row + b] = true;
      }
    }
    if (!explained) {
      for (std::size_t r = first_row; r < first_row + rows; ++r) flagged[r] = true;
    }
    i = end;
  }
  return flagged;
}

struct IntervalResidual {
  const PreparedRow* a;
  const PreparedRow* b;
  ModelConstants k;
  double inv_sigma;

  template <typename T>
  bool operator()(const T* p, T* r) const {
    const double dt = b->time_s - a->time_s;
    const T model = 0.5 * (row_accel(p, k, *a) + row_accel(p, k, *b));
    r[0] = ((b->speed_ms - a->speed_ms) / dt - model) * inv_sigma;
    return true;
  }
};

using IntervalCost = ceres::AutoDiffCostFunction<IntervalResidual, 1, kParamCount>;

class EquationError final : public Formulation {
 public:
  EquationError(const PreparedData& data, const ModelConstants& k) : data_(&data), k_(k) {}

  std::vector<double> residuals(const ParamVector& params) const override {
    std::vector<double> r;
    r.reserve(static_cast<std::size_t>(data_->used_intervals));
    for (const auto& log : data_->logs) {
      for (std::size_t i = 0; i < log.intervals.size(); ++i) {
        if (log.intervals[i] != IntervalStatus::Used) continue;
        r.push_back(equation_error_residual(log.rows[i], log.rows[i + 1], k_, params, nullptr));
      }
    }
    return r;
  }

  void add_blocks(ceres::Problem& problem, double* params, double sigma,
                  ceres::LossFunction* loss) override {
    for (const auto& log : data_->logs) {
      for (std::size_t i = 0; i < log.intervals.size(); ++i) {
        if (log.intervals[i] != IntervalStatus::Used) continue;
        problem.AddResidualBlock(
            new IntervalCost(new IntervalResidual{&log.rows[i], &log.rows[i + 1], k_, 1.0 / sigma}),
            loss, params);
      }
    }
  }

  double sigma_floor() const override { return 2e-4; }  // m/s^2
  ceres::LinearSolverType linear_solver() const override { return ceres::DENSE_QR; }
  bool sparse_covariance() const override { return false; }

  // Rows to blame for the discounted intervals (see attribute_rows).
  std::vector<DiscountedRow> discounted_rows(const ParamVector& params, double sigma,
                                             const FitSetup& setup) const override {
    std::vector<DiscountedRow> out;
    if (setup.loss == LossKind::None) return out;
    // |z| beyond which the loss weight falls below the discount weight.
    const double w = setup.discount_weight;
    const double c = setup.loss_scale;
    const double z_limit = setup.loss == LossKind::Cauchy ? c * std::sqrt(1.0 / w - 1.0) : c / w;
    for (const auto& log : data_->logs) {
      const std::size_t n = log.rows.size();
      const std::size_t m = n > 0 ? n - 1 : 0;
      std::vector<double> z(m, 0.0);
      std::vector<bool> used(m, false);
      for (std::size_t i = 0; i < m; ++i) {
        if (log.intervals[i] != IntervalStatus::Used) continue;
        used[i] = true;
        z[i] = equation_error_residual(log.rows[i], log.rows[i + 1], k_, params, nullptr) / sigma;
      }
      const std::vector<bool> flagged = attribute_rows(z, used, z_limit);
      for (std::size_t row = 0; row < n; ++row) {
        if (!flagged[row]) continue;
        DiscountedRow d;
        d.log_index = log.rows[row].log_index;
        d.source_row = log.rows[row].source_row;
        d.time_s = log.rows[row].time_s;
        for (std::size_t i : {row - 1, row}) {
          if (i >= m || !used[i]) continue;  // row - 1 wraps for row 0
          if (std::abs(z[i]) > std::abs(d.z)) {
            d.z = z[i];
            d.weight = robust_weight(setup.loss, setup.loss_scale, z[i]);
          }
        }
        out.push_back(d);
      }
    }
    return out;
  }

 private:
  const PreparedData* data_;
  ModelConstants k_;
};

}  // namespace

double equation_error_residual(const PreparedRow& a, const PreparedRow& b,
                               const ModelConstants& constants, const ParamVector& params,
                               double* jacobian) {
  const IntervalResidual f{&a, &b, constants, 1.0};
  if (jacobian == nullptr) {
    double r = 0.0;
    f(params.data(), &r);
    return r;
  }
  using Jet = ceres::Jet<double, kParamCount>;
  Jet p[kParamCount];
  for (int i = 0; i < kParamCount; ++i) p[i] = Jet(params[static_cast<std::size_t>(i)], i);
  Jet r;
  f(p, &r);
  for (int i = 0; i < kParamCount; ++i) jacobian[i] = r.v[i];
  return r.a;
}

std::unique_ptr<Formulation> make_equation_error(const PreparedData& data,
                                                 const ModelConstants& constants) {
  return std::make_unique<EquationError>(data, constants);
}

}  // namespace ecorail::fitting
