// Nelder-Mead downhill simplex for a few variables without derivatives: the switch points of a
// run under one time price (dp/cruise_polish.cpp). The cost of a run is smooth in each switch
// point but has kinks where a coast meets a lower limit's braking curve, and there one
// coordinate at a time stalls on the ridge the kink makes; a simplex moves along it. An
// infeasible point may score +inf; it is the worst vertex and is reflected away from.
#pragma once

#include <algorithm>
#include <cmath>
#include <numeric>
#include <vector>

namespace ecorail::dp {

struct NelderMeadResult {
  std::vector<double> x;  // the best vertex
  double f = 0.0;
  int evaluations = 0;
  bool converged = false;  // the simplex shrank below the tolerance (else the budget ran out)
};

// Minimises f from x0 with a first simplex of x0 and x0 + step * e_i; stops when every vertex
// lies within tolerance of the best in every coordinate, or after max_evaluations.
template <class Function>
NelderMeadResult nelder_mead_minimum(const Function& f, const std::vector<double>& x0, double step,
                                     double tolerance, int max_evaluations) {
  const std::size_t n = x0.size();
  NelderMeadResult out;
  std::vector<std::vector<double>> p(n + 1, x0);
  std::vector<double> fp(n + 1);
  for (std::size_t i = 0; i < n; ++i) p[i + 1][i] += step;
  for (std::size_t i = 0; i <= n; ++i) fp[i] = f(p[i]);
  out.evaluations = static_cast<int>(n + 1);
  std::vector<std::size_t> order(n + 1);
  auto at = [&](const std::vector<double>& c, const std::vector<double>& w, double t) {
    std::vector<double> x(n);
    for (std::size_t i = 0; i < n; ++i) x[i] = c[i] + t * (w[i] - c[i]);
    return x;
  };
  while (true) {
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t a, std::size_t b) { return fp[a] < fp[b]; });
    const std::size_t best = order.front(), worst = order.back(), second = order[n - 1];
    double extent = 0.0;
    for (std::size_t k = 0; k <= n; ++k) {
      for (std::size_t i = 0; i < n; ++i) extent = std::max(extent, std::abs(p[k][i] - p[best][i]));
    }
    if (extent <= tolerance) {
      out.converged = true;
      break;
    }
    if (out.evaluations >= max_evaluations) break;
    std::vector<double> centroid(n, 0.0);
    for (std::size_t k = 0; k <= n; ++k) {
      if (k == worst) continue;
      for (std::size_t i = 0; i < n; ++i) centroid[i] += p[k][i] / static_cast<double>(n);
    }
    const std::vector<double> xr = at(centroid, p[worst], -1.0);
    const double fr = f(xr);
    ++out.evaluations;
    if (fr < fp[best]) {
      const std::vector<double> xe = at(centroid, p[worst], -2.0);
      const double fe = f(xe);
      ++out.evaluations;
      if (fe < fr) {
        p[worst] = xe, fp[worst] = fe;
      } else {
        p[worst] = xr, fp[worst] = fr;
      }
      continue;
    }
    if (fr < fp[second]) {
      p[worst] = xr, fp[worst] = fr;
      continue;
    }
    // Contract towards the better of the worst vertex and its reflection.
    const bool outside = fr < fp[worst];
    const std::vector<double> xc = at(centroid, outside ? xr : p[worst], 0.5);
    const double fc = f(xc);
    ++out.evaluations;
    if (fc < (outside ? fr : fp[worst])) {
      p[worst] = xc, fp[worst] = fc;
      continue;
    }
    // Shrink every vertex towards the best.
    for (std::size_t k = 0; k <= n; ++k) {
      if (k == best) continue;
      p[k] = at(p[best], p[k], 0.5);
      fp[k] = f(p[k]);
      ++out.evaluations;
    }
  }
  const std::size_t best =
      static_cast<std::size_t>(std::min_element(fp.begin(), fp.end()) - fp.begin());
  out.x = p[best];
  out.f = fp[best];
  return out;
}

}  // namespace ecorail::dp
