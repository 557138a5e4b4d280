// The small pieces of the Newton steps on a run's switch points (dp/timing_journey_part.cpp,
// dp/timing_switch_descent.cpp): a dense linear solve of a handful of equations (Gaussian
// elimination with partial pivoting, in place), and the largest residual.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <utility>
#include <vector>

namespace ecorail::dp {

// Solves a x = b in place (a: n x n, row-major; x into b). False when a pivot is not above
// least_pivot (a singular a, or one too near it).
inline bool solve_dense(std::vector<double>& a, std::vector<double>& b, std::size_t n,
                        double least_pivot = 0.0) {
  for (std::size_t c = 0; c < n; ++c) {
    std::size_t piv = c;
    for (std::size_t i = c + 1; i < n; ++i) {
      if (std::abs(a[i * n + c]) > std::abs(a[piv * n + c])) piv = i;
    }
    if (!(std::abs(a[piv * n + c]) > least_pivot)) return false;
    if (piv != c) {
      for (std::size_t j = 0; j < n; ++j) std::swap(a[c * n + j], a[piv * n + j]);
      std::swap(b[c], b[piv]);
    }
    for (std::size_t i = c + 1; i < n; ++i) {
      const double f = a[i * n + c] / a[c * n + c];
      for (std::size_t j = c; j < n; ++j) a[i * n + j] -= f * a[c * n + j];
      b[i] -= f * b[c];
    }
  }
  for (std::size_t c = n; c-- > 0;) {
    for (std::size_t j = c + 1; j < n; ++j) b[c] -= a[c * n + j] * b[j];
    b[c] /= a[c * n + c];
  }
  return true;
}

// The largest |r_i| (0 for none): residuals are scaled so that 1 is met.
inline double max_abs(const std::vector<double>& r) {
  double worst = 0.0;
  for (double x : r) worst = std::max(worst, std::abs(x));
  return worst;
}

}  // namespace ecorail::dp
