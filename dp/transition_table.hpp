// TransitionTable: every DP transition integrated once. For each grid node and each control
// the train is driven from s_i to s_{i+1} with the physics integrator; the table keeps the
// energy cost, the time and where the end speed falls on the next stage (lower node and
// weight). None of this depends on the time price lambda, so a lambda search re-uses the table
// and each backward sweep is only a min over a few additions per node. Because each control is
// integrated over the step and the cost-to-go is interpolated at the true end speed, coasting
// is represented exactly even where it changes the speed by less than one speed step.
#pragma once

#include <cstdint>
#include <vector>

#include "dp/objective.hpp"
#include "dp/stage_grid.hpp"
#include "dp/stage_work.hpp"
#include "physics/control.hpp"
#include "physics/motion.hpp"

namespace ecorail::dp {

struct Transition {
  double energy_J = 0.0;
  double time_s = 0.0;
  double weight = 0.0;
  std::int32_t lower = -1;  // -1: infeasible (the train would stop short)
};

class TransitionTable {
 public:
  TransitionTable(const physics::Motion& motion, const StageGrid& grid, Objective objective,
                  const physics::StepSettings& step);
  // Which chunks of the next stage each chunk reads (for the sweep's scheduling).
  const ChunkDependencies& dependencies() const { return deps_; }
  const Transition& at(int node, physics::Control c) const {
    return table_[static_cast<std::size_t>(node) * physics::kControlCount + static_cast<int>(c)];
  }

 private:
  std::vector<Transition> table_;
  ChunkDependencies deps_;
};

}  // namespace ecorail::dp
