#include "fitting/identifiability.hpp"

#include <cmath>

#include <Eigen/Dense>

#include "data/csv_reader.hpp"
#include "data/input_error.hpp"
#include "fitting/equation_error.hpp"

namespace ecorail::fitting {

namespace {

std::string log_labels(const PreparedData& data) {
  std::string s;
  for (const auto& log : data.logs) s += (s.empty() ? "" : ", ") + log.label;
  return s.empty() ? std::string("<no log>") : s;
}

std::string reason_for(const ParamFlags& involved, const PreparedData& data) {
  auto has = [&](Param p) { return involved[static_cast<std::size_t>(p)]; };
  std::vector<std::string> reasons;
  if ((has(kRotatingMassFactor) || has(kMassT) || has(kTractionScale)) &&
      data.force_intervals == 0) {
    reasons.push_back(
        "no usable interval has a known traction or braking force, so the inertia cannot be "
        "told from the resistance scale");
  }
  if (has(kMassT) && has(kTractionScale) && data.braking_intervals == 0) {
    reasons.push_back(
        "mass and traction scale act only through their ratio unless braking forces are logged");
  }
  if (has(kMassT) && has(kRotatingMassFactor)) {
    reasons.push_back(
        "the logged forces see only the effective mass M (1 + rho); mass and mass factor "
        "separate only through the gradient's pull on the static mass, so gradient_scale must "
        "be held");
  }
  if (has(kGradientScale) && data.gradient_intervals == 0) {
    reasons.push_back("the logs show no gradient on the usable intervals");
  }
  if ((has(kDavisA) || has(kDavisB) || has(kDavisC)) &&
      data.max_speed_kmh - data.min_speed_kmh < 10.0) {
    reasons.push_back("the usable intervals span only " +
                      data::format_number(std::round(data.min_speed_kmh * 10) / 10) + " to " +
                      data::format_number(std::round(data.max_speed_kmh * 10) / 10) + " km/h");
  }
  std::string s;
  for (const auto& r : reasons) s += (s.empty() ? "" : "; ") + r;
  return s;
}

}  // namespace

void check_identifiable(const PreparedData& data, const ModelConstants& constants,
                        const ParamVector& start, const ParamFlags& fixed,
                        const IdentifiabilityOptions& options) {
  std::vector<int> free;
  ParamFlags free_flags{};
  for (int p = 0; p < kParamCount; ++p) {
    if (!fixed[static_cast<std::size_t>(p)]) {
      free.push_back(p);
      free_flags[static_cast<std::size_t>(p)] = true;
    }
  }
  const std::string labels = log_labels(data);
  if (free.empty()) {
    throw data::InputError(labels, 0, "", "at least one parameter to fit; all are fixed");
  }
  const int n_free = static_cast<int>(free.size());
  const int need = std::max(options.min_intervals, options.min_intervals_per_parameter * n_free);
  if (data.used_intervals < need) {
    std::string excluded;
    for (int s = 1; s < kIntervalStatusCount; ++s) {
      if (data.status_counts[s] == 0) continue;
      excluded += (excluded.empty() ? "" : ", ") + std::to_string(data.status_counts[s]) + " " +
                  std::string(interval_status_name(static_cast<IntervalStatus>(s)));
    }
    throw data::InputError(
        labels, 0, "",
        "enough rows to identify " + param_list(free_flags) + " (" + std::to_string(n_free) +
            " free parameters): at least " + std::to_string(need) +
            " usable one-row-to-the-next intervals; got " + std::to_string(data.used_intervals) +
            " from " + std::to_string(data.rows) + " rows" +
            (excluded.empty() ? std::string() : " (excluded: " + excluded + ")") +
            "; these parameters are not identifiable from these logs");
  }

  Eigen::MatrixXd J(data.used_intervals, n_free);
  int row = 0;
  double jac[kParamCount];
  for (const auto& log : data.logs) {
    for (std::size_t i = 0; i < log.intervals.size(); ++i) {
      if (log.intervals[i] != IntervalStatus::Used) continue;
      equation_error_residual(log.rows[i], log.rows[i + 1], constants, start, jac);
      for (int c = 0; c < n_free; ++c) J(row, c) = jac[free[static_cast<std::size_t>(c)]];
      ++row;
    }
  }
  ParamFlags involved{};
  bool any = false;
  for (int c = 0; c < n_free; ++c) {
    const double norm = J.col(c).norm();
    if (norm == 0.0) {
      involved[static_cast<std::size_t>(free[static_cast<std::size_t>(c)])] = true;
      any = true;
    } else {
      J.col(c) /= norm;
    }
  }
  if (!any) {
    Eigen::JacobiSVD<Eigen::MatrixXd> svd(J, Eigen::ComputeThinV);
    const auto& s = svd.singularValues();
    const double smax = s(0);
    for (int k = 0; k < s.size(); ++k) {
      if (s(k) > options.rank_tolerance * smax) continue;
      const Eigen::VectorXd v = svd.matrixV().col(k);
      for (int c = 0; c < n_free; ++c) {
        if (std::abs(v(c)) > 0.05) {
          involved[static_cast<std::size_t>(free[static_cast<std::size_t>(c)])] = true;
          any = true;
        }
      }
    }
  }
  if (!any) return;
  const std::string reason = reason_for(involved, data);
  int count = 0;
  for (bool b : involved) count += b ? 1 : 0;
  const std::string what =
      count == 1
          ? "logs that identify " + param_list(involved) + "; it is not identifiable from them"
          : "logs that tell " + param_list(involved) +
                " apart; these parameters are not identifiable from them";
  throw data::InputError(labels, 0, "",
                         what + (reason.empty() ? std::string() : " (" + reason + ")") +
                             ". Fix one of them with --fix NAME, or add logs with that excitation");
}

}  // namespace ecorail::fitting
