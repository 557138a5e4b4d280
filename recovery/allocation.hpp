// Exact allocation of a total running time over sections with convex energy-time frontiers:
// minimise sum_k E_k(t_k) subject to sum_k t_k = T and lower_k <= t_k <= upper_k. Each E_k is a
// dp::FrontierCurve (decreasing and convex where its points are), so the problem is convex and
// separable, and its optimum is characterised by the KKT conditions: one time price lambda with
// t_k = clamp(t_k(lambda), lower_k, upper_k), t_k(lambda) the time at which section k's
// marginal energy per second -E_k'(t) equals lambda (found by bisection on
// FrontierCurve::marginal_at, continuous and non-increasing on a convex curve). The sum
// of those times falls monotonically as lambda rises, so lambda is found by bisection (in log
// space after a bracketing walk); where a frontier is linear (constant marginal) the sum jumps,
// and the last step interpolates the times between the two ends of the final bracket, which
// closes the sum exactly. The result is the optimum of the frontier curves, not an
// approximation of it: the curves are the only approximation (within 0.01 % of exact solves,
// docs/frontiers.md). A summary reports the termination, the price and the bounds hit.
#pragma once

#include <string>
#include <vector>

#include "dp/frontier_curve.hpp"
#include "dp/termination.hpp"

namespace ecorail::recovery {

struct AllocationOptions {
  double time_tolerance_s = 1e-6;  // |sum t_k - T| at the end
  int max_iterations = 200;        // bisection steps
  // Checks every field; on failure writes one sentence naming the field into *error.
  bool IsValid(std::string* error) const;
};

// One section of the allocation: its frontier and the bounds on its running time (clamped to
// the frontier's domain).
struct AllocationItem {
  const dp::FrontierCurve* curve = nullptr;
  double lower_s = 0.0;
  double upper_s = 0.0;
};

// CONVERGENCE when the times add up to the total within the tolerance; FAILURE when the total
// lies below the sum of the lower bounds (no allocation exists). A total above the sum of the
// upper bounds puts every section at its upper bound (CONVERGENCE, time_left_s > 0: the train
// arrives early by that much).
struct AllocationSummary {
  dp::Termination termination = dp::Termination::FAILURE;
  int sections = 0;
  int iterations = 0;
  double total_time_s = 0.0;
  double allocated_time_s = 0.0;
  double time_left_s = 0.0;
  double lambda_J_per_s = 0.0;  // the common price of the sections not at a bound
  int at_lower = 0, at_upper = 0;
  double energy_J = 0.0;  // by the frontier curves
  std::string message;

  std::string BriefReport() const;
  std::string FullReport() const;
  bool IsSolutionUsable() const { return dp::is_usable(termination); }
};

struct AllocationResult {
  std::vector<double> times_s;
  std::vector<double> marginals_J_per_s;  // -E_k'(t_k), by the curve
  std::vector<double> energies_J;         // E_k(t_k), by the curve
  AllocationSummary summary;
};

// Options are checked first (std::invalid_argument), and every item must have a curve and
// lower <= upper inside the curve's domain (std::invalid_argument).
AllocationResult allocate_time(const std::vector<AllocationItem>& items, double total_time_s,
                               const AllocationOptions& options = {});

}  // namespace ecorail::recovery
