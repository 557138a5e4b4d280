// Robust statistics shared by the fits: the loss functions (in units of the noise scale, so a
// residual of z standard deviations costs rho(z^2)), the weight a loss gives a residual (the
// rows it "discounted" are the ones with a small weight), and the noise scale itself, estimated
// as 1.4826 times the median absolute residual so that the outliers a robust fit exists for
// cannot inflate it.
#pragma once

#include <memory>
#include <string_view>
#include <vector>

namespace ceres {
class LossFunction;
}

namespace ecorail::fitting {

enum class LossKind { None, Huber, Cauchy };

std::string_view loss_name(LossKind k);
// The loss at scale c (in units of sigma); nullptr for None.
std::unique_ptr<ceres::LossFunction> make_loss(LossKind kind, double c);
// Weight rho'(z^2) in [0, 1] of a residual of z sigmas.
double robust_weight(LossKind kind, double c, double z);
// 1.4826 * median |r|, floored.
double robust_sigma(const std::vector<double>& residuals, double floor);

}  // namespace ecorail::fitting
