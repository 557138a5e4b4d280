// The backward sweep: for a time price lambda (J/s), the cost-to-go
//   J_i(v) = min over controls [ energy + lambda * time + J_{i+1}(v') ]
// from the stop back to the start, with J_{i+1} interpolated linearly at the end speed v'.
// Each stage is parallel over its speed nodes with OpenMP; nodes are independent, so the result
// does not depend on the number of threads.
#pragma once

#include <cstdint>
#include <vector>

#include "dp/stage_grid.hpp"
#include "dp/transition_table.hpp"

namespace ecorail::dp {

inline constexpr double kInfeasible = 1e30;  // finite so interpolation never makes NaN
inline bool is_feasible(double cost) {
  return cost < 1e25;
}

struct ValueFunction {
  double lambda = 0.0;
  std::vector<double> cost_to_go;  // per global node
  std::vector<std::uint8_t> best;  // optimal control per global node

  // Cost-to-go at stage i interpolated at speed v.
  double at(const StageGrid& grid, int i, double v_ms) const;
};

void backward_sweep(const StageGrid& grid, const TransitionTable& table, double lambda,
                    ValueFunction& value);

}  // namespace ecorail::dp
