#include "dp/backward_sweep.hpp"

#include <omp.h>

#include <algorithm>

#include "dp/stage_barrier.hpp"

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
  // One parallel region for the whole sweep; each thread takes a fixed share of every stage's
  // nodes, so the result does not depend on the thread count or on scheduling.
  const int threads = std::max(1, std::min(omp_get_max_threads(), grid.node_count(0) / 16));
  StageBarrier barrier(threads);
#pragma omp parallel num_threads(threads)
  {
    const int me = omp_get_thread_num();
    const int team = omp_get_num_threads();
    for (int i = last - 1; i >= 0; --i) {
      const int begin = grid.offset(i);
      const int count = grid.node_count(i);
      const int lo = begin + static_cast<int>(static_cast<long>(count) * me / team);
      const int hi = begin + static_cast<int>(static_cast<long>(count) * (me + 1) / team);
      for (int node = lo; node < hi; ++node) {
        double best_cost = kInfeasible;
        std::uint8_t best_c = 0;
        for (int c = 0; c < physics::kControlCount; ++c) {
          const Transition& t = table.at(node, static_cast<physics::Control>(c));
          if (t.lower < 0) continue;
          double next = J[t.lower];
          if (t.weight > 0.0) next += t.weight * (J[t.lower + 1] - next);
          const double cost = t.energy_J + lambda * t.time_s + next;
          if (cost < best_cost) {
            best_cost = cost;
            best_c = static_cast<std::uint8_t>(c);
          }
        }
        J[node] = best_cost;
        best[node] = best_c;
      }
      if (team > 1) barrier.arrive_and_wait(last - 1 - i);
    }
  }
}

}  // namespace ecorail::dp
