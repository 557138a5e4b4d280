// Golden-section search for the minimum of a function that is unimodal on [a, b]: each step
// keeps the part of the bracket that holds the smaller of two interior values and re-uses the
// other one, so every step costs one evaluation. Used where a derivative is not at hand: the
// time a stop between two parts of a timing-point journey is passed (dp/timing_journey.cpp)
// and the multiplier of a pair bound's dual (energy/pair_bound.cpp). An infeasible point may score
// +inf; it moves the bracket away from itself.
#pragma once

#include <cmath>

namespace ecorail::dp {

struct GoldenSectionResult {
  double x = 0.0;  // the better of the last two interior points
  double f = 0.0;
  double best_x = 0.0;  // the best point evaluated anywhere in the search
  double best_f = 0.0;
  int evaluations = 0;
};

// Narrows [a, b] until it is no wider than tolerance or max_iterations steps are taken. On a
// tie the left part is kept when ties_go_left, else the right part.
template <class Function>
GoldenSectionResult golden_section_minimum(const Function& f, double a, double b, double tolerance,
                                           int max_iterations, bool ties_go_left) {
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  GoldenSectionResult out;
  double x1 = b - g * (b - a), x2 = a + g * (b - a);
  double f1 = f(x1), f2 = f(x2);
  out.evaluations = 2;
  auto left_wins = [&] { return ties_go_left ? f1 <= f2 : f1 < f2; };
  out.best_f = left_wins() ? f1 : f2;
  out.best_x = left_wins() ? x1 : x2;
  for (int it = 0; it < max_iterations && b - a > tolerance; ++it) {
    if (left_wins()) {
      b = x2, x2 = x1, f2 = f1;
      x1 = b - g * (b - a);
      f1 = f(x1);
    } else {
      a = x1, x1 = x2, f1 = f2;
      x2 = a + g * (b - a);
      f2 = f(x2);
    }
    ++out.evaluations;
    const double f_min = f1 < f2 ? f1 : f2;
    if (f_min < out.best_f) {
      out.best_f = f_min;
      out.best_x = f1 < f2 ? x1 : x2;
    }
  }
  out.x = left_wins() ? x1 : x2;
  out.f = left_wins() ? f1 : f2;
  return out;
}

}  // namespace ecorail::dp
