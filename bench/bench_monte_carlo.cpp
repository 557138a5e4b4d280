// Speed of the Monte Carlo days of question 3.2: simulated service days per second on the 2.1
// reference plan (100 trains over 63 900 s, the reference pattern) with the exact recovery and
// the seed paper's rule, on 1 and 2 threads. The section runs (knots every 1 s, 0.1 s power
// bins) are made once outside the timings and kept in the cache directory $ECORAIL_BENCH_CACHE
// (default test-cache/bench; laid out as `ecorail montecarlo --cache-dir`, and keyed as it keys
// them, so a directory the command filled serves the benchmark too).
// Run: ECORAIL_BENCH_CACHE=DIR build/bench/bench_monte_carlo --benchmark_min_time=2
#include <benchmark/benchmark.h>

#include <cstdio>
#include <cstdlib>
#include <memory>

#include "data/line_loader.hpp"
#include "data/route_builder.hpp"
#include "data/train_io.hpp"
#include "monte_carlo_days.hpp"
#include "recovery/monte_carlo.hpp"

namespace {

using namespace ecorail;

bench::DaysSetup& setup() {
  static bench::DaysSetup s = [] {
    bench::DaysSetup x;
    const auto line = data::default_line();
    const auto train = data::default_train();
    const auto stops = data::stops_between(line, "A1", "A14");
    char key[200];
    std::snprintf(key, sizeof key, "delay|%016llx|%016llx|600/R",
                  static_cast<unsigned long long>(line.checksum()),
                  static_cast<unsigned long long>(data::train_checksum(train)));
    x.library = std::make_unique<dp::SectionLibrary>(train, data::build_routes(line, stops, train),
                                                     dp::SectionLibraryOptions{}, key);
    dp::JourneyOptions journey;
    journey.measure_marginals = false;
    x.plan = recovery::reference_plan(*x.library, stops, journey);
    const char* env = std::getenv("ECORAIL_BENCH_CACHE");
    x.make_runs(env != nullptr && *env != 0 ? env : "test-cache/bench");
    return x;
  }();
  return s;
}

void Days(benchmark::State& state, recovery::RecoveryPolicy policy) {
  bench::DaysSetup& s = setup();
  recovery::MonteCarloOptions o;
  o.recovery = policy;
  const recovery::MonteCarlo mc(*s.library, s.plan, o, *s.runs);
  bench::time_days(state, mc, 8);
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
