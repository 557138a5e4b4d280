// Energy-time frontier of a section: the optimal energy at each running time from the minimum
// upwards. Each point is a full running-time solve (re-simulated) that takes exactly the path of
// a stand-alone solve for that time (solve_for_time with the same search options), so the two
// give the same run; the lattice prices every search walks are computed once per frontier
// (LatticeRuns). The frontier
// of an optimal-control problem is decreasing and convex; the grid can make it wobble by a
// little, and every place where it does is reported with its size rather than smoothed away.
#pragma once

#include <string>
#include <vector>

#include "dp/progress_callback.hpp"
#include "dp/section_engine.hpp"
#include "dp/termination.hpp"
#include "dp/time_target.hpp"

namespace ecorail::dp {

inline constexpr double kMaxFrontierPoints = 10000.0;  // (t_max - t_min) / step at most

struct FrontierOptions {
  double t_min_s = 0.0;  // 0: the section's minimum running time
  double t_max_s = 0.0;  // 0: minimum + 60 s
  double step_s = 1.0;
  TimeSearchOptions search;
  // A second difference below -convexity_tolerance * energy counts as a convexity wobble.
  double convexity_tolerance = 1e-5;
  // Called after each point ("point", done, total); may be empty.
  ProgressFn progress;
  // Checks every field; on failure writes one sentence naming the field into *error.
  bool IsValid(std::string* error) const;
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

// The report of a frontier, like a section's: CONVERGENCE when every point met its running
// time, NO_CONVERGENCE when some did not, FAILURE when there are no points. Wobbles of the
// grid (non-monotone or non-convex steps) are warnings, not failures.
struct FrontierSummary {
  std::string from, to;
  double min_time_s = 0.0;
  double t_first_s = 0.0, t_last_s = 0.0;  // running times of the first and last points
  int points = 0;
  int converged_points = 0;
  int evaluations = 0;  // lambda evaluations and trim re-simulations over all points
  double first_energy_kJ = 0.0, last_energy_kJ = 0.0;  // by the engine's objective
  bool monotone = true, convex = true;
  Termination termination = Termination::FAILURE;
  std::vector<std::string> warnings;

  std::string BriefReport() const;
  std::string FullReport() const;
  bool IsSolutionUsable() const { return is_usable(termination); }
};

FrontierSummary summarize_frontier(const Frontier& frontier, const std::string& from,
                                   const std::string& to);

// Options are checked before any work (std::invalid_argument).
Frontier compute_frontier(const SectionEngine& engine, const FrontierOptions& options);
// Fills wobbles, monotone and convex from the points.
void check_frontier_shape(Frontier& frontier, double convexity_tolerance);

}  // namespace ecorail::dp
