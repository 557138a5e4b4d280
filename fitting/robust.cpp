#include "fitting/robust.hpp"

#include <algorithm>
#include <cmath>

#include <ceres/loss_function.h>

namespace ecorail::fitting {

std::string_view loss_name(LossKind k) {
  switch (k) {
    case LossKind::None:
      return "none";
    case LossKind::Huber:
      return "huber";
    case LossKind::Cauchy:
      return "cauchy";
  }
  return "?";
}

std::unique_ptr<ceres::LossFunction> make_loss(LossKind kind, double c) {
  switch (kind) {
    case LossKind::None:
      return nullptr;
    case LossKind::Huber:
      return std::make_unique<ceres::HuberLoss>(c);
    case LossKind::Cauchy:
      return std::make_unique<ceres::CauchyLoss>(c);
  }
  return nullptr;
}

double robust_weight(LossKind kind, double c, double z) {
  const double a = std::abs(z);
  switch (kind) {
    case LossKind::None:
      return 1.0;
    case LossKind::Huber:
      return a <= c ? 1.0 : c / a;
    case LossKind::Cauchy:
      return 1.0 / (1.0 + (a / c) * (a / c));
  }
  return 1.0;
}

double robust_sigma(const std::vector<double>& residuals, double floor) {
  if (residuals.empty()) return floor;
  std::vector<double> a(residuals.size());
  std::transform(residuals.begin(), residuals.end(), a.begin(),
                 [](double r) { return std::abs(r); });
  const auto mid = a.begin() + static_cast<std::ptrdiff_t>(a.size() / 2);
  std::nth_element(a.begin(), mid, a.end());
  return std::max(1.4826 * *mid, floor);
}

}  // namespace ecorail::fitting
