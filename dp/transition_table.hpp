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

// One transition, its end located on the next stage: `lower` counts from that stage's first node
// (-1: infeasible, the train would stop short). No initialisers: the table's build writes every
// entry.
struct Transition {
  double energy_J;
  double time_s;
  double weight;
  std::int32_t lower;
};

class TransitionTable {
 public:
  // share = false integrates every entry stage by stage (the reference the tests compare with).
  TransitionTable(const physics::Motion& motion, const StageGrid& grid, Objective objective,
                  const physics::StepSettings& step, bool share = true);
  // Which chunks of the next stage each chunk reads (for the sweep's scheduling).
  const ChunkDependencies& dependencies() const { return deps_; }
  // The kControlCount transitions out of node j of stage i (lower counted on stage i + 1).
  const Transition* row(int i, int j) const {
    const StageRows& r = rows_[i];
    if (j >= r.shared_from && j < r.shared_to) {
      return class_rows_.data() + (r.class_row + j) * physics::kControlCount;
    }
    const long own = r.own_row + (j < r.shared_from ? j : j - (r.shared_to - r.shared_from));
    return own_rows_.data() + own * physics::kControlCount;
  }
  // The transition out of a node (its global index) by control c, lower as a global index too
  // (-1: infeasible). For callers that walk nodes, not stages; the sweep reads row().
  Transition at(int node, physics::Control c) const;
  // What the build did: classes of alike stages, transitions integrated once per class, and
  // entries integrated stage by stage or taken from a class.
  int stage_classes() const { return stage_classes_; }
  long class_integrations() const { return class_integrations_; }
  long stage_integrations() const { return stage_integrations_; }
  long shared_entries() const { return shared_entries_; }
  // The entries kept: the classes' rows and the stages' own rows (a stage reads its class's rows
  // where every control's transition is its own integration bit for bit).
  long stored_entries() const { return static_cast<long>(class_rows_.size() + own_rows_.size()); }

 private:
  // Where a stage's rows are: nodes [shared_from, shared_to) read the class's rows (from
  // class_row on), the others their own (from own_row on, in node order).
  struct StageRows {
    long class_row = 0, own_row = 0;
    int shared_from = 0, shared_to = 0;
  };
  std::vector<StageRows> rows_;
  std::vector<int> stage_offset_;  // the grid's first node of each stage, for at()
  std::vector<Transition> class_rows_;
  BigVector<Transition> own_rows_;
  ChunkDependencies deps_;
  int stage_classes_ = 0;
  long class_integrations_ = 0;
  long stage_integrations_ = 0;
  long shared_entries_ = 0;
};

}  // namespace ecorail::dp
