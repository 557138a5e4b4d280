#include "dp/transition_table.hpp"

#include <algorithm>

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
  // Dependency ranges of the sweep's chunks: the next-stage chunks any transition lands in.
  deps_.chunk_offset.assign(1, 0);
  for (int i = 0; i <= last; ++i) {
    const int chunks = (grid.node_count(i) + kSweepChunk - 1) / kSweepChunk;
    deps_.chunk_offset.push_back(deps_.chunk_offset.back() + chunks);
  }
  deps_.first.assign(deps_.chunk_offset.back(), 0);
  deps_.last.assign(deps_.chunk_offset.back(), -1);
  for (int i = 0; i < last; ++i) {
    const int begin = grid.offset(i);
    const int next_begin = grid.offset(i + 1);
    const int next_count = grid.node_count(i + 1);
    for (int c = 0; c < deps_.chunks(i); ++c) {
      int lo = next_count, hi = -1;
      const int end = std::min(begin + grid.node_count(i), begin + (c + 1) * kSweepChunk);
      for (int node = begin + c * kSweepChunk; node < end; ++node) {
        for (int k = 0; k < physics::kControlCount; ++k) {
          const Transition& t = at(node, static_cast<physics::Control>(k));
          if (t.lower < 0) continue;
          const int local = t.lower - next_begin;
          lo = std::min(lo, local);
          hi = std::max(hi, std::min(local + 1, next_count - 1));
        }
      }
      const int g = deps_.chunk_offset[i] + c;
      deps_.first[g] = hi < 0 ? 0 : lo / kSweepChunk;
      deps_.last[g] = hi < 0 ? -1 : hi / kSweepChunk;
    }
  }
}

}  // namespace ecorail::dp
