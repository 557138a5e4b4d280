// Energy-time frontier of a section: the optimal energy at each running time from the minimum
// upwards. Each point is a full running-time solve (re-simulated), warm-started from the
// previous point's lambda so a frontier costs a few lambda evaluations per point. The frontier
// of an optimal-control problem is decreasing and convex; the grid can make it wobble by a
// little, and every place where it does is reported with its size rather than smoothed away.
#pragma once

#include <string>
#include <vector>

#include "dp/section_engine.hpp"
#include "dp/time_target.hpp"

namespace ecorail::dp {

struct FrontierOptions {
  double t_min_s = 0.0;  // 0: the section's minimum running time
  double t_max_s = 0.0;  // 0: minimum + 60 s
  double step_s = 1.0;
  TimeSearchOptions search;
  // A second difference below -convexity_tolerance * energy counts as a convexity wobble.
  double convexity_tolerance = 1e-5;
};

struct FrontierPoint {
  double target_time_s = 0.0;
  double running_time_s = 0.0;  // re-simulated
  double traction_work_J = 0.0;
  double regen_J = 0.0;
  double net_J = 0.0;
  double cost_J = 0.0;  // by the engine's objective
  double lambda_J_per_s = 0.0;
  bool converged = false;
  int evaluations = 0;  // lambda evaluations + trim re-simulations spent on this point
};

struct FrontierWobble {
  double time_s = 0.0;
  std::string kind;  // "non_monotone" or "non_convex"
  double size_J = 0.0;
};

struct Frontier {
  double min_time_s = 0.0;
  std::vector<FrontierPoint> points;
  std::vector<FrontierWobble> wobbles;
  bool monotone = true;
  bool convex = true;
};

Frontier compute_frontier(const SectionEngine& engine, const FrontierOptions& options);
// Fills wobbles, monotone and convex from the points.
void check_frontier_shape(Frontier& frontier, double convexity_tolerance);

}  // namespace ecorail::dp
