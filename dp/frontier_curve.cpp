#include "dp/frontier_curve.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace ecorail::dp {

namespace {

// Over the first seconds after the minimum time the spline is built in sqrt(T - T_min).
constexpr double kRootZone_s = 4.0;

// Schumaker's knot inside [t0, t1] for end slopes d0, d1 and secant delta.
double knot(double t0, double t1, double d0, double d1, double delta) {
  const double h = t1 - t0;
  if ((d0 - delta) * (d1 - delta) >= 0.0) return 0.5 * (t0 + t1);
  if (std::abs(d1 - delta) < std::abs(d0 - delta)) {
    const double bar = t0 + 2.0 * h * (d1 - delta) / (d1 - d0);
    return 0.5 * (t0 + bar);
  }
  const double bar = t1 + 2.0 * h * (d0 - delta) / (d1 - d0);
  return 0.5 * (t1 + bar);
}

// The slope at each interior point from the parabola through it and its neighbours: a convex
// combination of the two secants. Ends: the parabola's slope, kept on the convex side of the
// end secant.
std::vector<double> parabola_slopes(const std::vector<double>& x, const std::vector<double>& e) {
  const std::size_t n = x.size();
  std::vector<double> delta(n - 1), d(n);
  for (std::size_t i = 0; i + 1 < n; ++i) delta[i] = (e[i + 1] - e[i]) / (x[i + 1] - x[i]);
  for (std::size_t i = 1; i + 1 < n; ++i) {
    const double h0 = x[i] - x[i - 1], h1 = x[i + 1] - x[i];
    d[i] = (h1 * delta[i - 1] + h0 * delta[i]) / (h0 + h1);
  }
  if (n == 2) {
    d[0] = d[1] = delta[0];
  } else {
    d[0] = std::min(2.0 * delta[0] - d[1], delta[0]);
    d[n - 1] = std::max(2.0 * delta[n - 2] - d[n - 2], delta[n - 2]);
    if (delta[n - 2] <= 0.0) d[n - 1] = std::min(d[n - 1], 0.0);  // a falling end stays falling
  }
  return d;
}

}  // namespace

void FrontierCurve::add_pieces(double t0, double t1, double x0, double x1, double e0, double e1,
                               double d0, double d1, bool in_root) {
  const double h = x1 - x0, delta = (e1 - e0) / h;
  const double t_ref = t_.front();
  auto t_of = [&](double x) { return in_root ? t_ref + x * x : x; };
  if (std::abs(d0 + d1 - 2.0 * delta) <= 1e-12 * (std::abs(delta) + 1.0)) {
    pieces_.push_back({t0, t1, x0, e0, d0, (d1 - d0) / (2.0 * h), in_root, t_ref});
    return;
  }
  const double xi = knot(x0, x1, d0, d1, delta);
  const double bar = (2.0 * delta * h - (xi - x0) * d0 - (x1 - xi) * d1) / h;  // slope at xi
  const double e_xi = e0 + 0.5 * (d0 + bar) * (xi - x0);
  const double t_xi = xi >= x1 ? t1 : t_of(xi);
  pieces_.push_back({t0, t_xi, x0, e0, d0, (bar - d0) / (2.0 * (xi - x0)), in_root, t_ref});
  pieces_.push_back({t_xi, t1, xi, e_xi, bar, (d1 - bar) / (2.0 * (x1 - xi)), in_root, t_ref});
}

FrontierCurve::FrontierCurve(const Frontier& frontier) : frontier_(frontier) {
  std::vector<double> e;
  for (const FrontierPoint& p : frontier.points) {
    if (!t_.empty() && !(p.running_time_s > t_.back())) {
      throw std::invalid_argument("frontier points must have strictly increasing running times");
    }
    t_.push_back(p.running_time_s);
    e.push_back(p.cost_J);
  }
  const std::size_t n = t_.size();
  if (n < 2) throw std::invalid_argument("a frontier curve needs at least two points");
  std::vector<double> d = parabola_slopes(t_, e);
  // The root zone: from a flat-out first point (infinite price) over its first seconds.
  std::size_t last_root = 0;
  if (n >= 3 && !std::isfinite(frontier.points.front().lambda_J_per_s)) {
    while (last_root + 1 < n && t_[last_root + 1] - t_[0] <= kRootZone_s + 1e-9) ++last_root;
  }
  if (last_root >= 1) {
    std::vector<double> u(last_root + 1), eu(e.begin(), e.begin() + last_root + 1);
    for (std::size_t i = 0; i <= last_root; ++i) u[i] = std::sqrt(t_[i] - t_[0]);
    std::vector<double> du = parabola_slopes(u, eu);
    if (last_root + 1 < n) {
      // Junction with the plain spline: one slope in t for both sides, convex on both.
      const std::size_t j = last_root;
      const double sigma = (e[j] - e[j - 1]) / (u[j] - u[j - 1]);
      const double right = (e[j + 1] - e[j]) / (t_[j + 1] - t_[j]);
      const double lo = sigma / (2.0 * u[j]);
      d[j] = lo <= right ? std::clamp(d[j], lo, right) : 0.5 * (lo + right);
      du[j] = 2.0 * u[j] * d[j];
    }
    for (std::size_t i = 0; i < last_root; ++i) {
      add_pieces(t_[i], t_[i + 1], u[i], u[i + 1], e[i], e[i + 1], du[i], du[i + 1], true);
    }
  }
  for (std::size_t i = last_root; i + 1 < n; ++i) {
    add_pieces(t_[i], t_[i + 1], t_[i], t_[i + 1], e[i], e[i + 1], d[i], d[i + 1], false);
  }
}

const FrontierCurve::Piece& FrontierCurve::piece_at(double time_s) const {
  if (!(time_s >= t_min_s() - 1e-9 && time_s <= t_max_s() + 1e-9)) {
    throw std::out_of_range("running time outside the frontier's domain");
  }
  const auto it = std::upper_bound(pieces_.begin(), pieces_.end(), time_s,
                                   [](double t, const Piece& p) { return t < p.t1; });
  return it == pieces_.end() ? pieces_.back() : *it;
}

double FrontierCurve::energy_at(double time_s) const {
  return piece_at(time_s).value(time_s);
}

double FrontierCurve::marginal_at(double time_s) const {
  return -piece_at(time_s).slope(time_s);
}

double FrontierCurve::time_for_marginal(double lambda) const {
  // The time that minimises E(t) + lambda t over the whole curve: on a convex stretch the time
  // whose marginal is lambda, and where a grid wobble leaves the curve locally non-convex (the
  // flat-out point and the first coasts a fraction of a second later can differ by little, so
  // the marginal dips just after t_min) still the minimiser a time price means. Searching only
  // for the first place the marginal reaches lambda returned t_min + 0.01 s there for any price
  // (A3 -> A4). Candidates: every piece's ends and its stationary point.
  if (!(lambda < std::numeric_limits<double>::infinity())) return t_min_s();
  const double target = -lambda;  // the slope sought
  double best_t = t_min_s();
  double best = energy_at(best_t) + lambda * best_t;
  const auto consider = [&](const Piece& p, double t) {
    t = std::clamp(t, p.t0, p.t1);
    const double cost = p.value(t) + lambda * t;
    if (cost < best) best = cost, best_t = t;
  };
  for (const Piece& p : pieces_) {
    consider(p, p.t0);
    consider(p, p.t1);
    // dE/dx = d0 + 2 c (x - x0); in the root zone dE/dt = dE/dx / (2 x).
    if (p.in_root) {
      const double den = 2.0 * p.c - 2.0 * target;
      if (den != 0.0) {
        const double x = (2.0 * p.c * p.x0 - p.d0) / den;
        if (x >= 0.0) consider(p, p.t_ref + x * x);
      }
    } else if (p.c != 0.0) {
      consider(p, p.x0 + (target - p.d0) / (2.0 * p.c));
    }
  }
  return best_t;
}

}  // namespace ecorail::dp
