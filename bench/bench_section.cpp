// Speed of the single-section engine on A6 -> A7 of the reference line at the default grid:
// one backward sweep, the lambda-independent transition table, and the whole solve for 110 s
// (engine build, lambda search, trim and fine re-simulation), and the whole line A1 -> A14 as a
// 13-section journey in 1726 s, each with 1 and 2 threads.
// Run: build/bench/bench_section --benchmark_min_time=1
#include <benchmark/benchmark.h>
#include <omp.h>

#include "data/line_loader.hpp"
#include "data/route_builder.hpp"
#include "data/train_io.hpp"
#include "dp/journey.hpp"
#include "dp/section_solve.hpp"

namespace {

using namespace ecorail;

struct Problem {
  physics::Train train = data::default_train();
  physics::Route route = data::build_route(data::default_line(), "A6", "A7", train);
};

const Problem& problem() {
  static const Problem p;
  return p;
}

// Args: threads, speed step in hundredths of km/h (20 = the default 0.2 km/h).
void BM_BackwardSweep(benchmark::State& state) {
  omp_set_num_threads(static_cast<int>(state.range(0)));
  dp::EngineOptions options;
  options.grid.dv_kmh = static_cast<double>(state.range(1)) / 100.0;
  const dp::SectionEngine engine(problem().train, problem().route, options);
  dp::ValueFunction value;
  for (auto _ : state) {
    dp::backward_sweep(engine.grid(), engine.transitions(), 7.1e5, value);
    benchmark::DoNotOptimize(value.cost_to_go.data());
  }
  state.counters["nodes"] = engine.grid().total_nodes();
}
BENCHMARK(BM_BackwardSweep)
    ->Args({1, 20})
    ->Args({2, 20})
    ->Args({1, 5})
    ->Args({2, 5})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

void BM_TransitionTable(benchmark::State& state) {
  omp_set_num_threads(static_cast<int>(state.range(0)));
  for (auto _ : state) {
    const dp::SectionEngine engine(problem().train, problem().route, {});
    benchmark::DoNotOptimize(&engine);
  }
}
BENCHMARK(BM_TransitionTable)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_SolveA6A7_110s(benchmark::State& state) {
  omp_set_num_threads(static_cast<int>(state.range(0)));
  double energy = 0.0;
  for (auto _ : state) {
    const auto sol = dp::solve_section(problem().train, problem().route, 110.0, {});
    energy = sol.run.sim.energy.traction_work_J;
  }
  state.counters["traction_kJ"] = energy / 1000.0;
}
BENCHMARK(BM_SolveA6A7_110s)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_JourneyA1A14_1726s(benchmark::State& state) {
  omp_set_num_threads(static_cast<int>(state.range(0)));
  const data::Line line = data::default_line();
  const auto stops = data::stops_between(line, "A1", "A14");
  std::vector<physics::Route> routes;
  for (std::size_t i = 0; i + 1 < stops.size(); ++i) {
    routes.push_back(data::build_route(line, stops[i], stops[i + 1], problem().train));
  }
  dp::JourneyOptions options;
  options.measure_marginals = false;
  double energy = 0.0;
  for (auto _ : state) {
    const auto sol =
        dp::solve_journey(problem().train, routes, std::vector<double>(12, 30.0), 1726.0, options);
    energy = sol.traction_work_J;
  }
  state.counters["traction_kJ"] = energy / 1000.0;
}
BENCHMARK(BM_JourneyA1A14_1726s)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
