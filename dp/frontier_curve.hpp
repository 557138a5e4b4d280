// FrontierCurve: a section's energy-time frontier as a function. Between the computed points
// it interpolates with Schumaker's shape-preserving quadratic spline: the slopes at the points
// are the three-point (parabola) estimates, which lie between the neighbouring secants, so on
// data that decrease and are convex the curve decreases and is convex too, and its derivative
// is continuous and piecewise linear. The marginal energy per second (the time price, -dE/dT)
// can then be read at any running time and inverted exactly: the running time at which the
// section's price equals a given lambda, as the optimal split of a journey needs. Near the
// minimum time of a frontier that starts at the flat-out run the spline is built in
// u = sqrt(T - T_min) instead: there a coast of length x saves energy in proportion to x but
// time in proportion to x^2, so E falls like -sqrt(T - T_min), with an infinite slope at T_min,
// and is smooth in u. A spline decreasing and convex in u is decreasing and convex in T. Energies
// are the engine objective's cost (J), times are running times (s).
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "dp/frontier.hpp"

namespace ecorail::dp {

class FrontierCurve {
 public:
  FrontierCurve() = default;
  // Needs at least two points with strictly increasing running times.
  explicit FrontierCurve(const Frontier& frontier);

  double t_min_s() const { return t_.front(); }
  double t_max_s() const { return t_.back(); }
  // Interpolated energy (J); outside [t_min, t_max] throws std::out_of_range.
  double energy_at(double time_s) const;
  // -dE/dT (J/s) at a running time inside the domain.
  double marginal_at(double time_s) const;
  // The running time that minimises E(t) + lambda t over the domain: on a convex curve the time
  // whose marginal equals lambda (t_min when lambda is above the marginal there, t_max when
  // below the marginal at t_max); where grid wobble leaves the curve locally non-convex, the
  // global minimiser, so that it is non-increasing in lambda as a time price requires.
  double time_for_marginal(double lambda_J_per_s) const;
  const Frontier& frontier() const { return frontier_; }

 private:
  // One quadratic piece on [t0, t1] in a variable x: x = t (plain) or x = sqrt(t - t_ref)
  // (root zone): E = e0 + (d0 + c (x - x0)) (x - x0).
  struct Piece {
    double t0, t1, x0, e0, d0, c;
    bool in_root = false;
    double t_ref = 0.0;
    double x_of(double t) const { return in_root ? std::sqrt(std::max(0.0, t - t_ref)) : t; }
    double value(double t) const {
      const double x = x_of(t) - x0;
      return e0 + (d0 + c * x) * x;
    }
    // dE/dt.
    double slope(double t) const {
      const double dedx = d0 + 2.0 * c * (x_of(t) - x0);
      if (!in_root) return dedx;
      const double u = x_of(t);
      return u > 0.0 ? dedx / (2.0 * u) : (dedx < 0.0 ? -INFINITY : 0.0);
    }
  };
  void add_pieces(double t0, double t1, double x0, double x1, double e0, double e1, double d0,
                  double d1, bool in_root);
  const Piece& piece_at(double time_s) const;

  Frontier frontier_;
  std::vector<double> t_;
  std::vector<Piece> pieces_;
};

}  // namespace ecorail::dp
