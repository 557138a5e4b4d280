// Cost and value of the window bound (energy/window_bound.hpp) on question 2.1's reference case
// (100 trains, span 63900 s, headways 120-660 s, the reference pattern at the model's default
// 0.01 s step): the whole bound (tables and multiplier search) on the bound grid the argument
// names (bins per second), with the bound on the used regenerated energy, the DP runs, the
// dual's floor and the time of the tables as counters; the bound restricted to the core; and the
// exact refinement (energy/window_refine.hpp) of the start the search builds from the core's
// maximisers; the exact optimum of the core (energy/window_span_optimum.hpp). The pattern and the
// model are built outside the timings. Run: build/bench/bench_window_bound   (or under valgrind
// --tool=callgrind with
// --benchmark_filter=.../1 for instruction counts)
#include <benchmark/benchmark.h>

#include <memory>
#include <vector>

#include "data/line_loader.hpp"
#include "data/route_builder.hpp"
#include "data/train_io.hpp"
#include "energy/power_flow_model.hpp"
#include "energy/window_bound.hpp"
#include "energy/window_refine.hpp"
#include "energy/window_span_optimum.hpp"
#include "fleet/fleet_pattern.hpp"
#include "fleet/fleet_problem.hpp"
#include "fleet/relaxed_start.hpp"
#include "reference_pattern.hpp"

namespace {

using namespace ecorail;

const energy::PowerFlowModel& reference_model() {
  static const std::unique_ptr<energy::PowerFlowModel> m = [] {
    const fleet::PatternTrip& p = bench::reference_pattern();
    return std::make_unique<energy::PowerFlowModel>(p.trip, fleet::limits_of({}),
                                                    energy::EnergyModelOptions{});
  }();
  return *m;
}

void BM_WindowBound(benchmark::State& state) {
  const energy::PowerFlowModel& m = reference_model();
  energy::WindowBoundOptions o;
  o.bound_ticks_per_second = static_cast<int>(state.range(0));
  for (auto _ : state) {
    const energy::WindowBound b = energy::window_used_regen_bound(m.profile(), m.limits(), o);
    state.counters["bound_used_kJ"] = b.bound_used_J / 1e3;
    state.counters["dp_runs"] = b.evaluations;
    state.counters["tables_s"] = b.tables_s;
    state.counters["dual_floor_kJ"] = b.dual_floor_J / 1e3;
  }
}
BENCHMARK(BM_WindowBound)->Arg(1)->Arg(2)->Arg(10)->Unit(benchmark::kSecond)->Iterations(1);

// The same bound with every headway in the core (522-660 s, where at most four trains share the
// line): a bound for those timetables only, not a certificate for the reference problem; what
// is left of its gap is the grid's and the multiplier's.
void BM_WindowBoundCoreOnly(benchmark::State& state) {
  const energy::PowerFlowModel& m = reference_model();
  energy::FleetLimits core = m.limits();
  core.headway_min_s = 522;
  energy::WindowBoundOptions o;
  o.bound_ticks_per_second = static_cast<int>(state.range(0));
  for (auto _ : state) {
    const energy::WindowBound b = energy::window_used_regen_bound(m.profile(), core, o);
    state.counters["bound_used_kJ"] = b.bound_used_J / 1e3;
    state.counters["dp_runs"] = b.evaluations;
    state.counters["core_min_s"] = b.core_min_s;
  }
}
BENCHMARK(BM_WindowBoundCoreOnly)
    ->Arg(2)
    ->Arg(10)
    ->Arg(100)
    ->Unit(benchmark::kSecond)
    ->Iterations(1);

// The exact refinement (default options, a headway moves by up to 3 s a pass) of the joined start
// from the core relaxation's maximisers (fleet/relaxed_start.hpp), which the search anneals:
// the used energy before and after, the passes and the window terms computed.
void BM_WindowRefineOfTheRelaxedStart(benchmark::State& state) {
  const energy::PowerFlowModel& m = reference_model();
  const std::vector<int> start =
      fleet::relaxed_start_headways(m.relaxation_maximisers_s(), fleet::FleetProblem{});
  for (auto _ : state) {
    const energy::WindowRefineSummary r = energy::window_refine(m.profile(), m.limits(), start);
    state.counters["start_used_kJ"] = r.start_used_J / 1e3;
    state.counters["used_kJ"] = r.used_J / 1e3;
    state.counters["passes"] = r.passes;
    state.counters["window_terms"] = static_cast<double>(r.window_terms);
  }
}
BENCHMARK(BM_WindowRefineOfTheRelaxedStart)->Unit(benchmark::kSecond)->Iterations(1);

// The exact optimum of the core (energy/window_span_optimum.hpp: every headway in 522-660 s,
// the span kept) on the model's grid, pruned by an incumbent: argument 0 the refined join nearest
// the span (the refine bench's result), 1 the refined best join (where the search's first round
// starts from): its used energy, whether it beat the incumbent, the relaxed bound, the states the
// exact DP kept and the time of the window terms. A better incumbent prunes more.
void BM_WindowSpanOptimumOfTheCore(benchmark::State& state) {
  const energy::PowerFlowModel& m = reference_model();
  std::vector<int> incumbent;
  if (state.range(0) == 0) {
    incumbent = energy::window_refine(m.profile(), m.limits(),
                                      fleet::relaxed_start_headways(m.relaxation_maximisers_s(),
                                                                    fleet::FleetProblem{}))
                    .headways_s;
  } else {
    double best = -1.0;
    for (const std::vector<int>& join :
         fleet::relaxed_start_candidates(m.relaxation_maximisers_s(), fleet::FleetProblem{})) {
      const energy::WindowRefineSummary r = energy::window_refine(m.profile(), m.limits(), join);
      if (r.applicable && r.used_J > best) best = r.used_J, incumbent = r.headways_s;
    }
  }
  for (auto _ : state) {
    const energy::WindowSpanSummary r =
        energy::window_span_optimum(m.profile(), m.limits(), incumbent);
    state.counters["incumbent_used_kJ"] = r.incumbent_used_J / 1e3;
    state.counters["used_kJ"] = r.used_J / 1e3;
    state.counters["improved"] = r.improved;
    state.counters["relaxed_bound_kJ"] = r.dual_bound_J / 1e3;
    state.counters["exact_states"] = static_cast<double>(r.exact_states);
    state.counters["terms_s"] = r.terms_s;
  }
}
BENCHMARK(BM_WindowSpanOptimumOfTheCore)->Arg(0)->Arg(1)->Unit(benchmark::kSecond)->Iterations(1);

}  // namespace

BENCHMARK_MAIN();
