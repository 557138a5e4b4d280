// Nelder-Mead search for the minimum of a function of a few variables without derivatives:
// a simplex of n + 1 points is reflected, expanded, contracted or shrunk towards its best point
// (the standard coefficients 1, 2, 1/2, 1/2). Used where the function is one solve of a DP per
// evaluation and its variables are coupled, so that searching one coordinate at a time crawls
// along a valley: the speeds of the points pinned in a part the label search ran
// (dp/timing_binding_pins.hpp), where two points 100 m apart that must be 9 s apart want the
// same speed. An infeasible point may score +inf; it is the simplex's worst and is moved first.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <numeric>
#include <vector>

namespace ecorail::dp {

struct NelderMeadResult {
  std::vector<double> x;  // the best point evaluated
  double f = 0.0;
  int evaluations = 0;
  bool converged = false;  // the simplex shrank below the tolerance (else the budget ran out)
};

// Starts from x0 and the n points x0 + step_i e_i; stops when every vertex lies within
// tolerance of the best in every coordinate (converged) or once max_evaluations evaluations are
// spent (a shrink under way is finished, so up to n more).
template <class Function>
NelderMeadResult nelder_mead_minimum(const Function& f, const std::vector<double>& x0,
                                     const std::vector<double>& step, double tolerance,
                                     int max_evaluations) {
  const std::size_t n = x0.size();
  NelderMeadResult out;
  std::vector<std::vector<double>> p(n + 1, x0);
  std::vector<double> fp(n + 1);
  auto eval = [&](const std::vector<double>& x) {
    ++out.evaluations;
    return f(x);
  };
  fp[0] = eval(p[0]);
  for (std::size_t i = 0; i < n; ++i) {
    p[i + 1][i] += step[i];
    fp[i + 1] = eval(p[i + 1]);
  }
  std::vector<std::size_t> order(n + 1);
  auto sort_simplex = [&] {
    std::iota(order.begin(), order.end(), std::size_t{0});
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t a, std::size_t b) { return fp[a] < fp[b]; });
  };
  auto spread = [&] {
    double d = 0.0;
    for (std::size_t k = 1; k <= n; ++k) {
      for (std::size_t i = 0; i < n; ++i)
        d = std::max(d, std::abs(p[order[k]][i] - p[order[0]][i]));
    }
    return d;
  };
  // x = c + t (worst - c): t = -1 reflects, -2 expands, 1/2 contracts inside.
  auto along = [&](const std::vector<double>& c, const std::vector<double>& worst, double t) {
    std::vector<double> x(n);
    for (std::size_t i = 0; i < n; ++i) x[i] = c[i] + t * (worst[i] - c[i]);
    return x;
  };
  sort_simplex();
  while (out.evaluations < max_evaluations) {
    if (spread() <= tolerance) {
      out.converged = true;
      break;
    }
    const std::size_t best = order[0], worst = order[n], second = order[n - 1];
    std::vector<double> c(n, 0.0);
    for (std::size_t k = 0; k < n; ++k) {
      for (std::size_t i = 0; i < n; ++i) c[i] += p[order[k]][i] / static_cast<double>(n);
    }
    const std::vector<double> xr = along(c, p[worst], -1.0);
    const double fr = eval(xr);
    if (fr < fp[best]) {
      const std::vector<double> xe = along(c, p[worst], -2.0);
      const double fe = eval(xe);
      if (fe < fr) {
        p[worst] = xe, fp[worst] = fe;
      } else {
        p[worst] = xr, fp[worst] = fr;
      }
    } else if (fr < fp[second]) {
      p[worst] = xr, fp[worst] = fr;
    } else {
      const std::vector<double> xc = along(c, p[worst], 0.5);
      const double fc = eval(xc);
      if (fc < fp[worst]) {
        p[worst] = xc, fp[worst] = fc;
      } else {  // shrink towards the best (whole, so every vertex keeps its own value)
        for (std::size_t k = 1; k <= n; ++k) {
          std::vector<double>& x = p[order[k]];
          for (std::size_t i = 0; i < n; ++i) x[i] = p[best][i] + 0.5 * (x[i] - p[best][i]);
          fp[order[k]] = eval(x);
        }
      }
    }
    sort_simplex();
  }
  out.x = p[order[0]];
  out.f = fp[order[0]];
  return out;
}

}  // namespace ecorail::dp
