#include "dp/backward_sweep.hpp"

#include <omp.h>

#include <algorithm>

#include "dp/stage_work.hpp"

namespace ecorail::dp {

double ValueFunction::at(const StageGrid& grid, int i, double v_ms) const {
  int lower;
  double w;
  grid.locate(i, v_ms, &lower, &w);
  const double lo = cost_to_go[lower];
  return w > 0.0 ? lo + w * (cost_to_go[lower + 1] - lo) : lo;
}

void backward_sweep(const StageGrid& grid, const TransitionTable& table, double lambda,
                    ValueFunction& value) {
  const int last = grid.stage_count() - 1;
  value.lambda = lambda;
  value.cost_to_go.assign(grid.total_nodes(), kInfeasible);
  value.best.assign(grid.total_nodes(), 0);
  value.cost_to_go[grid.offset(last)] = 0.0;  // at rest at the stop
  double* J = value.cost_to_go.data();
  std::uint8_t* best = value.best.data();
  // One parallel region for the whole sweep, scheduled chunk by chunk on data dependencies
  // (see stage_work.hpp).
  // Inside another parallel region (a journey runs its sections side by side) the sweep keeps
  // to its own thread.
  const int threads =
      omp_in_parallel()
          ? 1
          : std::max(1, std::min(omp_get_max_threads(), grid.node_count(0) / kSweepChunk));
  StageWork work(table.dependencies(), threads);
  work.mark_stage_done(last);
#pragma omp parallel num_threads(threads)
  {
    const int me = omp_get_thread_num();
    for (int i = last - 1; i >= 0; --i) {
      const int begin = grid.offset(i);
      const int end_of_stage = begin + grid.node_count(i);
      for (int c = work.take(i, me); c >= 0; c = work.take(i, me)) {
        work.wait_for_inputs(i, c);
        const int end = std::min(end_of_stage, begin + (c + 1) * kSweepChunk);
        for (int node = begin + c * kSweepChunk; node < end; ++node) {
          double best_cost = kInfeasible;
          std::uint8_t best_c = 0;
          for (int k = 0; k < physics::kControlCount; ++k) {
            const Transition& t = table.at(node, static_cast<physics::Control>(k));
            if (t.lower < 0) continue;
            double next = J[t.lower];
            if (t.weight > 0.0) next += t.weight * (J[t.lower + 1] - next);
            const double cost = t.energy_J + lambda * t.time_s + next;
            if (cost < best_cost) {
              best_cost = cost;
              best_c = static_cast<std::uint8_t>(k);
            }
          }
          J[node] = best_cost;
          best[node] = best_c;
        }
        work.finish(i, c);
      }
    }
  }
}

}  // namespace ecorail::dp
