// LambdaBracket: the one root search of the library, for a function that falls as x grows. The
// single-section and the journey running-time searches use it with x = log(lambda) and f(x) =
// running time - target; the switch-point trim with x the position of the switch and the cruise
// polish with x the start of the hold, f the re-simulated time error (both through the second
// constructor, with the bracket they have found). The bracket is found by stepping x from a
// starting point until f changes sign, then narrowed by regula falsi (Illinois variant, which
// halves a stale end's value so the bracket keeps shrinking from both sides). The caller scores
// every evaluation itself and says when it is close enough. f may return +infinity for "no
// usable run, treat as too slow" (a run that does not reach the stop); an infinite end makes the
// step a bisection. The one search for a minimum is dp/golden_section.hpp.
#pragma once

#include <functional>

namespace ecorail::dp {

class LambdaBracket {
 public:
  using Function = std::function<double(double x)>;

  // Evaluates f at x0 and steps by `step` (in log lambda) until the root is bracketed, within
  // lambda in [1, 1e12] J/s and the evaluation budget.
  LambdaBracket(Function f, double x0, double step, int max_evaluations);
  // A bracket already known: f(x_lo) = f_lo >= 0, f(x_hi) = f_hi <= 0, x_lo < x_hi.
  LambdaBracket(Function f, double x_lo, double f_lo, double x_hi, double f_hi,
                int max_evaluations);
  // Narrows until done() holds, the bracket is narrower than min_width (a jump of the ragged
  // running time lies inside it) or the budget is spent.
  void narrow(const std::function<bool()>& done, double min_width = 1e-4);
  bool bracketed() const { return f_lo_ >= 0.0 && f_hi_ <= 0.0; }
  int evaluations() const { return evaluations_; }

 private:
  double evaluate(double x);

  Function f_;
  int max_evaluations_;
  int evaluations_ = 0;
  double x_lo_ = 0.0, f_lo_ = 0.0, x_hi_ = 0.0, f_hi_ = 0.0;
  int side_ = 0;
};

}  // namespace ecorail::dp
