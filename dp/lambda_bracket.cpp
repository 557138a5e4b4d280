#include "dp/lambda_bracket.hpp"

#include <cmath>

namespace ecorail::dp {

double LambdaBracket::evaluate(double x) {
  ++evaluations_;
  return f_(x);
}

LambdaBracket::LambdaBracket(Function f, double x0, double step, int max_evaluations)
    : f_(std::move(f)), max_evaluations_(max_evaluations) {
  x_lo_ = x_hi_ = x0;
  f_lo_ = f_hi_ = evaluate(x0);
  // f(lo) > 0 (too slow), f(hi) < 0 (too fast).
  while (f_lo_ < 0.0 && evaluations_ < max_evaluations_ && x_lo_ > 0.0) {
    x_hi_ = x_lo_, f_hi_ = f_lo_;
    x_lo_ -= step;
    f_lo_ = evaluate(x_lo_);
  }
  while (f_hi_ > 0.0 && evaluations_ < max_evaluations_ && x_hi_ < std::log(1e12)) {
    x_lo_ = x_hi_, f_lo_ = f_hi_;
    x_hi_ += step;
    f_hi_ = evaluate(x_hi_);
  }
}

LambdaBracket::LambdaBracket(Function f, double x_lo, double f_lo, double x_hi, double f_hi,
                             int max_evaluations)
    : f_(std::move(f)),
      max_evaluations_(max_evaluations),
      x_lo_(x_lo),
      f_lo_(f_lo),
      x_hi_(x_hi),
      f_hi_(f_hi) {}

void LambdaBracket::narrow(const std::function<bool()>& done, double min_width) {
  while (bracketed() && !done() && evaluations_ < max_evaluations_ && x_hi_ - x_lo_ > min_width) {
    double xm = std::isfinite(f_lo_) && std::isfinite(f_hi_)
                    ? (x_lo_ * f_hi_ - x_hi_ * f_lo_) / (f_hi_ - f_lo_)
                    : 0.5 * (x_lo_ + x_hi_);
    if (!(xm > x_lo_ && xm < x_hi_)) xm = 0.5 * (x_lo_ + x_hi_);
    const double fm = evaluate(xm);
    if (fm > 0.0) {
      x_lo_ = xm, f_lo_ = fm;
      if (side_ == -1) f_hi_ *= 0.5;
      side_ = -1;
    } else {
      x_hi_ = xm, f_hi_ = fm;
      if (side_ == 1) f_lo_ *= 0.5;
      side_ = 1;
    }
  }
}

}  // namespace ecorail::dp
