#include "recovery/allocation.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include "dp/lambda_bracket.hpp"

namespace ecorail::recovery {

namespace {

double sum_of(const std::vector<double>& v) {
  double s = 0.0;
  for (double x : v) s += x;
  return s;
}

// The running time at which a section's marginal energy per second equals lambda, within its
// bounds: the library's root search (dp::LambdaBracket) on the sign of the curve's marginal less
// lambda, which is continuous and non-increasing on a convex frontier (FrontierCurve::marginal_at;
// its time_for_marginal minimises over the whole curve, not within the bounds, see
// docs/delays.md). On the sign only (+-infinity), every step halves the bracket (LambdaBracket
// bisects when an end is infinite): the time is found to 1e-10 s in at most about 40 steps
// whatever the kinks of the marginal, where the frontier's linear pieces join.
double time_at_price(const AllocationItem& it, double lambda) {
  const double inf = std::numeric_limits<double>::infinity();
  const double a = it.lower_s, b = it.upper_s;
  if (!(lambda < it.curve->marginal_at(a))) return a;
  if (lambda <= it.curve->marginal_at(b)) return b;
  double lo = a, hi = b;  // marginal above lambda at lo, at or below it at hi
  dp::LambdaBracket bracket(
      [&](double t) {
        const bool above = it.curve->marginal_at(t) > lambda;
        (above ? lo : hi) = t;
        return above ? inf : -inf;
      },
      a, inf, b, -inf, 200);
  bracket.narrow([] { return false; }, 1e-10);
  return 0.5 * (lo + hi);
}

// Each section's time at price lambda, clamped to its bounds.
std::vector<double> times_at(const std::vector<AllocationItem>& items, double lambda) {
  std::vector<double> t(items.size());
  for (std::size_t k = 0; k < items.size(); ++k) t[k] = time_at_price(items[k], lambda);
  return t;
}

}  // namespace

bool AllocationOptions::IsValid(std::string* error) const {
  auto fail = [&](const char* text) {
    if (error != nullptr) *error = text;
    return false;
  };
  if (!(time_tolerance_s > 0.0 && time_tolerance_s < 1.0))
    return fail("AllocationOptions::time_tolerance_s must lie in (0, 1) s");
  if (max_iterations < 1 || max_iterations > 10000)
    return fail("AllocationOptions::max_iterations must lie in [1, 10000]");
  return true;
}

std::string AllocationSummary::BriefReport() const {
  char buf[400];
  std::snprintf(buf, sizeof buf,
                "allocation of %.3f s over %d sections: lambda %.3f kJ/s, %d at the minimum "
                "time, %d at the upper bound, %d iterations, %s",
                total_time_s, sections, lambda_J_per_s / 1e3, at_lower, at_upper, iterations,
                std::string(dp::status_word(termination, message.empty() ? 0 : 1)).c_str());
  return buf;
}

std::string AllocationSummary::FullReport() const {
  char buf[800];
  std::snprintf(buf, sizeof buf,
                "Allocation (bisection on the common marginal energy per second)\n"
                "  sections            %d\n  total time          %.6f s\n"
                "  allocated           %.6f s\n  time left (early)   %.6f s\n"
                "  lambda              %.6f kJ/s\n  at minimum time     %d\n"
                "  at upper bound      %d\n  energy (frontiers)  %.1f kJ\n"
                "  iterations          %d\n  termination         %s\n",
                sections, total_time_s, allocated_time_s, time_left_s, lambda_J_per_s / 1e3,
                at_lower, at_upper, energy_J / 1e3, iterations,
                std::string(dp::termination_name(termination)).c_str());
  std::string out = buf;
  if (!message.empty()) out += "  note                " + message + "\n";
  return out;
}

AllocationResult allocate_time(const std::vector<AllocationItem>& items, double total_time_s,
                               const AllocationOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw std::invalid_argument(why);
  if (items.empty()) throw std::invalid_argument("allocate_time: no sections");
  if (!std::isfinite(total_time_s)) throw std::invalid_argument("allocate_time: total not finite");
  double sum_lo = 0.0, sum_hi = 0.0;
  for (const AllocationItem& it : items) {
    if (it.curve == nullptr) throw std::invalid_argument("allocate_time: a section has no curve");
    if (!(it.lower_s <= it.upper_s) || it.lower_s < it.curve->t_min_s() - 1e-9 ||
        it.upper_s > it.curve->t_max_s() + 1e-9)
      throw std::invalid_argument(
          "allocate_time: bounds must satisfy t_min <= lower <= upper <= t_max of the frontier");
    sum_lo += it.lower_s;
    sum_hi += it.upper_s;
  }
  AllocationResult r;
  AllocationSummary& s = r.summary;
  s.sections = static_cast<int>(items.size());
  s.total_time_s = total_time_s;
  const double tol = options.time_tolerance_s;
  auto finish = [&](std::vector<double> t, double lambda) {
    r.times_s = std::move(t);
    s.lambda_J_per_s = lambda;
    s.allocated_time_s = sum_of(r.times_s);
    s.time_left_s = std::max(0.0, total_time_s - s.allocated_time_s);
    for (std::size_t k = 0; k < items.size(); ++k) {
      const double t_k = r.times_s[k];
      r.energies_J.push_back(items[k].curve->energy_at(t_k));
      r.marginals_J_per_s.push_back(items[k].curve->marginal_at(t_k));
      s.energy_J += r.energies_J.back();
      if (t_k <= items[k].lower_s + 1e-9) ++s.at_lower;
      if (t_k >= items[k].upper_s - 1e-9) ++s.at_upper;
    }
  };
  if (total_time_s < sum_lo - tol) {
    s.termination = dp::Termination::FAILURE;
    char buf[200];
    std::snprintf(buf, sizeof buf, "total %.3f s is below the sum of the minimum times %.3f s",
                  total_time_s, sum_lo);
    s.message = buf;
    return r;
  }
  if (total_time_s >= sum_hi - tol) {
    std::vector<double> t;
    for (const AllocationItem& it : items) t.push_back(it.upper_s);
    double lambda = 0.0;  // the largest price at which every section stays at its upper bound
    for (const AllocationItem& it : items)
      lambda = std::max(lambda, it.curve->marginal_at(it.upper_s));
    finish(std::move(t), lambda);
    if (total_time_s > sum_hi + tol) s.message = "every section at its upper bound; arrives early";
    s.termination = dp::Termination::CONVERGENCE;
    return r;
  }
  // Bracket: sum(lo_lambda) >= T >= sum(hi_lambda).
  double lo = 1e3, hi = 1e3;
  while (sum_of(times_at(items, lo)) < total_time_s && lo > 1e-9) lo /= 4.0;
  if (sum_of(times_at(items, lo)) < total_time_s) lo = 0.0;
  while (sum_of(times_at(items, hi)) > total_time_s && hi < 1e15) hi *= 4.0;
  if (sum_of(times_at(items, hi)) > total_time_s) hi = std::numeric_limits<double>::infinity();
  int it = 0;
  for (; it < options.max_iterations; ++it) {
    std::vector<double> ta = times_at(items, lo), tb = times_at(items, hi);
    if (sum_of(ta) - sum_of(tb) <= tol) break;
    double mid;
    if (lo > 0.0 && std::isfinite(hi))
      mid = std::sqrt(lo * hi);
    else if (!std::isfinite(hi))
      mid = std::max(1.0, lo) * 4.0;
    else
      mid = hi / 4.0;
    if (!(mid > lo && mid < hi)) break;  // the bracket is as narrow as doubles allow
    if (sum_of(times_at(items, mid)) >= total_time_s)
      lo = mid;
    else
      hi = mid;
  }
  s.iterations = it;
  // Close the sum exactly between the bracket's ends (a linear piece of a frontier has one
  // marginal over an interval of times: the sum jumps there, and any split of the jump is optimal).
  const std::vector<double> ta = times_at(items, lo), tb = times_at(items, hi);
  const double sa = sum_of(ta), sb = sum_of(tb);
  const double theta = sa - sb > 0.0 ? std::clamp((total_time_s - sb) / (sa - sb), 0.0, 1.0) : 1.0;
  std::vector<double> t(items.size());
  for (std::size_t k = 0; k < items.size(); ++k) t[k] = tb[k] + theta * (ta[k] - tb[k]);
  finish(std::move(t), std::isfinite(hi) ? (lo > 0.0 ? std::sqrt(lo * hi) : hi) : lo);
  s.termination = std::fabs(s.allocated_time_s - total_time_s) <= tol
                      ? dp::Termination::CONVERGENCE
                      : dp::Termination::NO_CONVERGENCE;
  if (s.termination != dp::Termination::CONVERGENCE)
    s.message = "the times do not add up to the total within the tolerance";
  return r;
}

}  // namespace ecorail::recovery
