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
  // One parallel region for the whole sweep; stages are cut into chunks that threads take as
  // they come (see stage_work.hpp).
  constexpr int kChunk = 32;
  StageWork work(last);
  const int threads = std::max(1, std::min(omp_get_max_threads(), grid.node_count(0) / kChunk));
#pragma omp parallel num_threads(threads)
  for (int i = last - 1; i >= 0; --i) {
    const int begin = grid.offset(i);
    const int count = grid.node_count(i);
    const int chunks = (count + kChunk - 1) / kChunk;
    for (int c = work.take(i, chunks); c >= 0; c = work.take(i, chunks)) {
      const int end = std::min(begin + count, begin + (c + 1) * kChunk);
      for (int node = begin + c * kChunk; node < end; ++node) {
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
      work.finish(i);
    }
    work.wait(i, chunks);
  }
}

}  // namespace ecorail::dp
