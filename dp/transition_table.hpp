// TransitionTable: every DP transition integrated once. For each grid node and each control
// the train is driven from s_i to s_{i+1} with the physics integrator; the table keeps the
// energy cost, the time and where the end speed falls on the next stage (lower node and
// weight). None of this depends on the time price lambda, so a lambda search re-uses the table
// and each backward sweep is only a min over a few additions per node. Because each control is
// integrated over the step and the cost-to-go is interpolated at the true end speed, coasting
// is represented exactly even where it changes the speed by less than one speed step.
//
// Most stages are alike: the same substeps on the same gradient, curve and tunnel drag, the
// same uniform speed row (0, dv, 2 dv, ...). A transition from such a node is integrated once
// per class of alike stages without supervising the speed envelope, and used for every stage of
// the class where the envelope cannot bind (the largest energy along it stays at or below the
// envelope at every substep end of that stage) and the train does not come to rest; the
// result is then bit for bit what that stage's own integration gives. The top node, transitions
// the envelope may bend and those that stop are integrated stage by stage, as before.
#pragma once

#include <cstdint>
#include <vector>

#include "base/big_blocks.hpp"
#include "dp/objective.hpp"
#include "dp/stage_grid.hpp"
#include "dp/stage_work.hpp"
#include "physics/control.hpp"
#include "physics/motion.hpp"

namespace ecorail::dp {

// No initialisers: the table's build writes every entry, so the table's memory (hundreds of
// megabytes on a long section) is first touched by the build's threads, not cleared before.
struct Transition {
  double energy_J;
  double time_s;
  double weight;
  std::int32_t lower;  // -1: infeasible (the train would stop short)
};

class TransitionTable {
 public:
  // share = false integrates every entry stage by stage (the reference the tests compare with).
  TransitionTable(const physics::Motion& motion, const StageGrid& grid, Objective objective,
                  const physics::StepSettings& step, bool share = true);
  // Which chunks of the next stage each chunk reads (for the sweep's scheduling).
  const ChunkDependencies& dependencies() const { return deps_; }
  const Transition& at(int node, physics::Control c) const {
    return table_[static_cast<std::size_t>(node) * physics::kControlCount + static_cast<int>(c)];
  }
  // What the build did: classes of alike stages, transitions integrated once per class, and
  // entries integrated stage by stage or taken from a class.
  int stage_classes() const { return stage_classes_; }
  long class_integrations() const { return class_integrations_; }
  long stage_integrations() const { return stage_integrations_; }
  long shared_entries() const { return shared_entries_; }

 private:
  BigVector<Transition> table_;
  ChunkDependencies deps_;
  int stage_classes_ = 0;
  long class_integrations_ = 0;
  long stage_integrations_ = 0;
  long shared_entries_ = 0;
};

}  // namespace ecorail::dp
