// The backward sweep: for a time price lambda (J/s), the cost-to-go
//   J_i(v) = min over controls [ energy + lambda * time + J_{i+1}(v') ]
// from the stop back to the start, with J_{i+1} interpolated linearly at the end speed v'.
// Each stage is parallel over its speed nodes with OpenMP; nodes are independent, so the result
// does not depend on the number of threads.
#pragma once

#include <cstdint>
#include <vector>

#include "base/big_blocks.hpp"
#include "dp/stage_grid.hpp"
#include "dp/stage_prices.hpp"
#include "dp/transition_table.hpp"

namespace ecorail::dp {

inline constexpr double kInfeasible = 1e30;  // finite so interpolation never makes NaN
inline bool is_feasible(double cost) {
  return cost < 1e25;
}

struct ValueFunction {
  double lambda = 0.0;
  // With stage prices: the price of each transition out of stage i (empty: lambda everywhere).
  std::vector<double> stage_lambda;
  BigVector<double> cost_to_go;  // per global node
  BigVector<std::uint8_t> best;  // optimal control per global node

  // Cost-to-go at stage i interpolated at speed v.
  double at(const StageGrid& grid, int i, double v_ms) const;
  // The time price of the transition out of stage i.
  double price(int i) const { return stage_lambda.empty() ? lambda : stage_lambda[i]; }
  // Bands on the transitions out of a stage (SpeedBand::at_fraction > 0), which the run's
  // extraction must keep as the sweep did; the one out of stage i or nullptr.
  std::vector<SpeedBand> transition_bands;
  const SpeedBand* transition_band(int i) const {
    return transition_bands.empty() ? nullptr : find_transition_band(i);
  }
  const SpeedBand* find_transition_band(int i) const;
};

void backward_sweep(const StageGrid& grid, const TransitionTable& table, double lambda,
                    ValueFunction& value);
// The same with a price per stage and speed bands (dp/stage_prices.hpp); value.lambda is set to
// the last stage's price.
void backward_sweep(const StageGrid& grid, const TransitionTable& table, const StagePrices& prices,
                    ValueFunction& value);

}  // namespace ecorail::dp
