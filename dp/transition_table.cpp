#include "dp/transition_table.hpp"

namespace ecorail::dp {

TransitionTable::TransitionTable(const physics::Motion& motion, const StageGrid& grid,
                                 Objective objective, const physics::StepSettings& step) {
  const int last = grid.stage_count() - 1;
  table_.resize(static_cast<std::size_t>(grid.offset(last)) * physics::kControlCount);
  // Flatten (stage, node) so the threads share the work evenly; each entry is independent, so
  // the table is the same whatever the thread count.
  std::vector<int> stage_of(grid.offset(last));
  for (int i = 0; i < last; ++i) {
    for (int j = 0; j < grid.node_count(i); ++j) stage_of[grid.offset(i) + j] = i;
  }
  const int total = grid.offset(last);
#pragma omp parallel for schedule(dynamic, 64)
  for (int node = 0; node < total; ++node) {
    const int i = stage_of[node];
    const double v = grid.speed(i, node - grid.offset(i));
    for (int c = 0; c < physics::kControlCount; ++c) {
      const auto control = static_cast<physics::Control>(c);
      Transition& t = table_[static_cast<std::size_t>(node) * physics::kControlCount + c];
      const physics::Advance adv =
          motion.advance(grid.position(i), 0.5 * v * v, grid.position(i + 1), control, step);
      if (adv.stalled) continue;
      t.energy_J = energy_cost_J(objective, motion.train(), adv.traction_work_J, adv.brake_work_J);
      t.time_s = adv.time_s;
      grid.locate(i + 1, physics::speed_from_e(adv.e_end), &t.lower, &t.weight);
    }
  }
}

}  // namespace ecorail::dp
