#include "fitting/output_error.hpp"

#include <cmath>

namespace ecorail::fitting {

namespace {

struct Segment {
  const PreparedLog* log = nullptr;
  std::size_t first = 0;  // row where the node sits
  std::size_t last = 0;   // row the simulation runs to (the next node, or the run's end)
  std::size_t last_measured = 0;
  bool continues = false;  // the next segment's node sits at `last`
};

// Speed at row j of a segment simulated from v0 at its first row.
template <typename T>
T simulate_to(const T* p, const ModelConstants& k, const PreparedLog& log, std::size_t first,
              std::size_t j, T v) {
  for (std::size_t m = first; m < j; ++m)
    v = integrate_interval(p, k, v, log.rows[m], log.rows[m + 1]);
  return v;
}

struct RowResidual {
  const PreparedLog* log;
  std::size_t first;
  std::size_t row;
  ModelConstants k;
  double inv_sigma;

  template <typename T>
  bool operator()(const T* p, const T* node, T* r) const {
    const T v = simulate_to(p, k, *log, first, row, node[0]);
    r[0] = (log->rows[row].speed_ms - v) * inv_sigma;
    return true;
  }
};

struct ContinuityResidual {
  const PreparedLog* log;
  std::size_t first;
  std::size_t last;
  ModelConstants k;
  double inv_sigma;

  template <typename T>
  bool operator()(const T* p, const T* node, const T* next_node, T* r) const {
    const T v = simulate_to(p, k, *log, first, last, node[0]);
    r[0] = (v - next_node[0]) * inv_sigma;
    return true;
  }
};

using RowCost = ceres::AutoDiffCostFunction<RowResidual, 1, kParamCount, 1>;
using ContinuityCost = ceres::AutoDiffCostFunction<ContinuityResidual, 1, kParamCount, 1, 1>;

class OutputError final : public Formulation {
 public:
  OutputError(const PreparedData& data, const ModelConstants& k, const OutputErrorOptions& opt)
      : k_(k), opt_(opt) {
    const std::size_t len = static_cast<std::size_t>(std::max(1, opt.segment_rows));
    for (const auto& log : data.logs) {
      std::size_t i = 0;
      const std::size_t n = log.intervals.size();
      while (i < n) {
        if (log.intervals[i] != IntervalStatus::Used) {
          ++i;
          continue;
        }
        std::size_t end = i;  // run of used intervals i..end-1, rows i..end
        while (end < n && log.intervals[end] == IntervalStatus::Used) ++end;
        for (std::size_t s = i; s < end; s += len) {
          Segment seg;
          seg.log = &log;
          seg.first = s;
          seg.last = std::min(s + len, end);
          seg.continues = seg.last < end;
          seg.last_measured = seg.continues ? seg.last - 1 : seg.last;
          segments_.push_back(seg);
          nodes_.push_back(log.rows[s].speed_ms);
        }
        i = end;
      }
    }
  }

  std::vector<double> residuals(const ParamVector& params) const override {
    std::vector<double> r;
    for (std::size_t s = 0; s < segments_.size(); ++s) {
      const Segment& seg = segments_[s];
      double v = nodes_[s];
      for (std::size_t j = seg.first; j <= seg.last_measured; ++j) {
        if (j > seg.first) {
          v = integrate_interval(params.data(), k_, v, seg.log->rows[j - 1], seg.log->rows[j]);
        }
        r.push_back(seg.log->rows[j].speed_ms - v);
      }
    }
    return r;
  }

  void add_blocks(ceres::Problem& problem, double* params, double sigma,
                  ceres::LossFunction* loss) override {
    const double inv_sigma = 1.0 / sigma;
    const double inv_cont = 1.0 / (opt_.continuity_fraction * sigma);
    for (std::size_t s = 0; s < segments_.size(); ++s) {
      const Segment& seg = segments_[s];
      double* node = &nodes_[s];
      for (std::size_t j = seg.first; j <= seg.last_measured; ++j) {
        problem.AddResidualBlock(new RowCost(new RowResidual{seg.log, seg.first, j, k_, inv_sigma}),
                                 loss, params, node);
      }
      if (seg.continues) {
        problem.AddResidualBlock(
            new ContinuityCost(new ContinuityResidual{seg.log, seg.first, seg.last, k_, inv_cont}),
            nullptr, params, node, &nodes_[s + 1]);
      }
    }
  }

  double sigma_floor() const override { return 2e-4; }  // m/s
  ceres::LinearSolverType linear_solver() const override { return ceres::SPARSE_NORMAL_CHOLESKY; }
  bool sparse_covariance() const override { return true; }

  std::vector<DiscountedRow> discounted_rows(const ParamVector& params, double sigma,
                                             const FitSetup& setup) const override {
    std::vector<DiscountedRow> out;
    for (std::size_t s = 0; s < segments_.size(); ++s) {
      const Segment& seg = segments_[s];
      double v = nodes_[s];
      for (std::size_t j = seg.first; j <= seg.last_measured; ++j) {
        if (j > seg.first) {
          v = integrate_interval(params.data(), k_, v, seg.log->rows[j - 1], seg.log->rows[j]);
        }
        const double z = (seg.log->rows[j].speed_ms - v) / sigma;
        const double w = robust_weight(setup.loss, setup.loss_scale, z);
        if (w < setup.discount_weight) {
          const PreparedRow& row = seg.log->rows[j];
          out.push_back({row.log_index, row.source_row, row.time_s, z, w});
        }
      }
    }
    return out;
  }

 private:
  ModelConstants k_;
  OutputErrorOptions opt_;
  std::vector<Segment> segments_;
  std::vector<double> nodes_;
};

}  // namespace

std::unique_ptr<Formulation> make_output_error(const PreparedData& data,
                                               const ModelConstants& constants,
                                               const OutputErrorOptions& options) {
  return std::make_unique<OutputError>(data, constants, options);
}

}  // namespace ecorail::fitting
