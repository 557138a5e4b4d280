#include "dp/backward_sweep.hpp"

#include <omp.h>

#include <algorithm>
#include <stdexcept>

#include "dp/stage_work.hpp"

namespace ecorail::dp {

double ValueFunction::at(const StageGrid& grid, int i, double v_ms) const {
  int lower;
  double w;
  grid.locate(i, v_ms, &lower, &w);
  const double lo = cost_to_go[lower];
  return w > 0.0 ? lo + w * (cost_to_go[lower + 1] - lo) : lo;
}

const SpeedBand* ValueFunction::find_transition_band(int i) const {
  for (const SpeedBand& b : transition_bands) {
    if (b.stage == i) return &b;
  }
  return nullptr;
}

namespace {

// Whether transition t out of node j of stage i passes its band's point (at_fraction of the
// way to stage i + 1) inside the band: v^2 linear in the distance between the node's speed and
// the speed it reaches (interpolated between the next stage's nodes as the sweep does).
bool passes_inside(const StageGrid& grid, int i, int j, const Transition& t,
                   const SpeedBand& band) {
  const double v0 = grid.speed(i, j);
  double v1 = grid.speed(i + 1, t.lower);
  if (t.weight > 0.0) v1 += t.weight * (grid.speed(i + 1, t.lower + 1) - v1);
  return band.passes(v0 * v0, v1 * v1, band.at_fraction);
}

// The nodes of one stage of a sweep: each node's best control and cost-to-go. The transition
// band's test is compiled only into the stages that have one (kTransitionBand): in the loop of
// every stage it cost 6 % more instructions in a single-price sweep.
struct StageSweep {
  const StageGrid& grid;
  const TransitionTable& table;
  int i, begin, next_offset;
  double lambda;
  const SpeedBand* band;             // on the stage's nodes, or nullptr
  const SpeedBand* transition_band;  // on its transitions, or nullptr
  double* J;
  std::uint8_t* best;

  template <bool kTransitionBand>
  void nodes(int from, int to) const {
    const double* J_next = J + next_offset;
    for (int node = from; node < to; ++node) {
      double best_cost = kInfeasible;
      std::uint8_t best_c = 0;
      const Transition* out = table.row(i, node - begin);
      for (int k = 0; k < physics::kControlCount; ++k) {
        const Transition& t = out[k];
        if (t.lower < 0) continue;
        if constexpr (kTransitionBand) {
          if (!passes_inside(grid, i, node - begin, t, *transition_band)) continue;
        }
        double next = J_next[t.lower];
        if (t.weight > 0.0) next += t.weight * (J_next[t.lower + 1] - next);
        const double cost = t.energy_J + lambda * t.time_s + next;
        if (cost < best_cost) {
          best_cost = cost;
          best_c = static_cast<std::uint8_t>(k);
        }
      }
      if (band != nullptr) {
        // Outside the timing point's speed window: no run may pass here.
        const double v = grid.speed(i, node - begin);
        if (v < band->min_ms || v > band->max_ms) best_cost = kInfeasible;
      }
      J[node] = best_cost;
      best[node] = best_c;
    }
  }
};

// The sweep for a price per stage (price(i): the price of a transition out of stage i) and, if
// band_of is not empty, the speed band of each stage (nullptr: none). One body for both forms,
// so a constant price makes the same arithmetic as the single-price sweep. end_band (nullptr:
// at rest at the stop) is the speed band of a run that ends moving: every node of the last
// stage inside it ends the run at cost 0.
template <typename PriceOf>
void sweep(const StageGrid& grid, const TransitionTable& table, const PriceOf& price_of,
           const std::vector<const SpeedBand*>& band_of, ValueFunction& value,
           const SpeedBand* end_band = nullptr) {
  const int last = grid.stage_count() - 1;
  // Not filled first: the sweep writes every node of stages 0 .. last - 1 (BigVector's resize
  // leaves new elements unwritten), and the last stage is set here.
  value.cost_to_go.resize(grid.total_nodes());
  value.best.resize(grid.total_nodes());
  std::fill(value.cost_to_go.begin() + grid.offset(last), value.cost_to_go.end(), kInfeasible);
  std::fill(value.best.begin() + grid.offset(last), value.best.end(), std::uint8_t{0});
  value.cost_to_go[grid.offset(last)] = 0.0;  // at rest at the stop
  if (end_band != nullptr) {
    for (int j = 0; j < grid.node_count(last); ++j) {
      const double v = grid.speed(last, j);
      const bool inside = v >= end_band->min_ms - 1e-9 && v <= end_band->max_ms + 1e-9;
      value.cost_to_go[grid.offset(last) + j] = inside ? 0.0 : kInfeasible;
    }
  }
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
      const double lambda = price_of(i);
      const SpeedBand* band = band_of.empty() ? nullptr : band_of[i];
      const SpeedBand* transition_band =
          band != nullptr && band->at_fraction > 0.0 ? band : nullptr;
      if (transition_band != nullptr) band = nullptr;
      const int begin = grid.offset(i);
      const int end_of_stage = begin + grid.node_count(i);
      const StageSweep at{grid, table,           i, begin, grid.offset(i + 1), lambda,
                          band, transition_band, J, best};
      for (int c = work.take(i, me); c >= 0; c = work.take(i, me)) {
        work.wait_for_inputs(i, c);
        const int from = begin + c * kSweepChunk;
        const int to = std::min(end_of_stage, begin + (c + 1) * kSweepChunk);
        if (transition_band != nullptr) {
          at.nodes<true>(from, to);
        } else {
          at.nodes<false>(from, to);
        }
        work.finish(i, c);
      }
    }
  }
}

}  // namespace

void backward_sweep(const StageGrid& grid, const TransitionTable& table, double lambda,
                    ValueFunction& value) {
  value.lambda = lambda;
  value.stage_lambda.clear();
  value.transition_bands.clear();
  sweep(
      grid, table, [lambda](int) { return lambda; }, {}, value);
}

void backward_sweep(const StageGrid& grid, const TransitionTable& table, const StagePrices& prices,
                    ValueFunction& value) {
  const int last = grid.stage_count() - 1;
  if (static_cast<int>(prices.lambda_J_per_s.size()) != last) {
    throw std::invalid_argument("stage prices: one price per transition (stage_count - 1) needed");
  }
  std::vector<const SpeedBand*> band_of;
  if (!prices.bands.empty()) {
    band_of.assign(grid.stage_count(), nullptr);
    for (const SpeedBand& b : prices.bands) {
      if (b.stage < 0 || b.stage >= last) {
        throw std::invalid_argument("stage prices: a speed band's stage is outside the grid");
      }
      band_of[b.stage] = &b;
    }
  }
  value.lambda = prices.lambda_J_per_s.back();
  value.stage_lambda = prices.lambda_J_per_s;
  value.transition_bands.clear();
  for (const SpeedBand& b : prices.bands) {
    if (b.at_fraction > 0.0) value.transition_bands.push_back(b);
  }
  const std::vector<double>& lambdas = prices.lambda_J_per_s;
  const SpeedBand end_band{last, prices.end_min_ms, prices.end_max_ms};
  sweep(
      grid, table, [&lambdas](int i) { return lambdas[i]; }, band_of, value,
      prices.end_moving ? &end_band : nullptr);
}

}  // namespace ecorail::dp
