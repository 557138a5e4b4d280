// Speed of the Monte Carlo days of question 3.2: simulated service days per second on the 2.1
// reference plan (100 trains over 63 900 s, the reference pattern) with the exact recovery and
// the seed paper's rule, on 1 and 2 threads. The section runs (knots every 1 s, 0.1 s power
// bins) are made once outside the timings and kept in build/test-cache/bench-section-runs.
// Run: build/bench/bench_monte_carlo --benchmark_min_time=2
#include <benchmark/benchmark.h>

#include <memory>

#include "data/line_loader.hpp"
#include "data/route_builder.hpp"
#include "data/train_io.hpp"
#include "output/frontier_cache.hpp"
#include "output/section_run_cache.hpp"
#include "recovery/monte_carlo.hpp"

namespace {

using namespace ecorail;

struct Setup {
  std::unique_ptr<dp::SectionLibrary> library;
  recovery::Plan plan;
  std::unique_ptr<output::FileFrontierStore> frontiers;
  std::unique_ptr<output::FileSectionRunStore> store;
  std::unique_ptr<recovery::SectionRuns> runs;
};

Setup& setup() {
  static Setup s = [] {
    Setup x;
    const auto line = data::default_line();
    const auto train = data::default_train();
    const auto stops = data::stops_between(line, "A1", "A14");
    x.library = std::make_unique<dp::SectionLibrary>(
        train, data::build_routes(line, stops, train), dp::SectionLibraryOptions{},
        "bench-montecarlo|" + std::to_string(line.checksum()) + "|" +
            std::to_string(data::train_checksum(train)));
    dp::JourneyOptions journey;
    journey.measure_marginals = false;
    x.plan = recovery::reference_plan(*x.library, stops, journey);
    x.frontiers = std::make_unique<output::FileFrontierStore>("test-cache/bench-frontiers");
    x.store = std::make_unique<output::FileSectionRunStore>("test-cache/bench-section-runs");
    x.runs = std::make_unique<recovery::SectionRuns>(*x.library, x.frontiers.get(), 1.0, 0.1,
                                                     x.store.get());
    return x;
  }();
  return s;
}

void Days(benchmark::State& state, recovery::RecoveryPolicy policy) {
  Setup& s = setup();
  recovery::MonteCarloOptions o;
  o.recovery = policy;
  const recovery::MonteCarlo mc(*s.library, s.plan, o, *s.runs);
  const int threads = static_cast<int>(state.range(0));
  const std::uint64_t days = 8;
  std::uint64_t first = 0;
  for (auto _ : state) {
    const auto records = mc.run_days(first, first + days, threads);
    benchmark::DoNotOptimize(records.data());
    first += days;
  }
  state.counters["days_per_s"] = benchmark::Counter(static_cast<double>(state.iterations() * days),
                                                    benchmark::Counter::kIsRate);
}

void BM_ExactDays(benchmark::State& state) {
  Days(state, recovery::RecoveryPolicy::Exact);
}
void BM_RuleDays(benchmark::State& state) {
  Days(state, recovery::RecoveryPolicy::Rule);
}

BENCHMARK(BM_ExactDays)->Arg(1)->Arg(2)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_RuleDays)->Arg(1)->Arg(2)->UseRealTime()->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
