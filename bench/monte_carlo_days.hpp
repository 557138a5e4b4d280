// The timing loop of the Monte Carlo benchmarks: each iteration runs the next `days` days of mc
// (never the same days twice, so no day is answered from a cache) on state.range(0) threads, and
// the counter days_per_s is simulated days per second of wall time.
#pragma once

#include <benchmark/benchmark.h>

#include <cstdint>

#include "recovery/monte_carlo.hpp"

namespace ecorail::bench {

inline void time_days(benchmark::State& state, const recovery::MonteCarlo& mc, std::uint64_t days) {
  const int threads = static_cast<int>(state.range(0));
  std::uint64_t first = 0;
  for (auto _ : state) {
    const auto records = mc.run_days(first, first + days, threads);
    benchmark::DoNotOptimize(records.data());
    first += days;
  }
  state.counters["days_per_s"] = benchmark::Counter(static_cast<double>(state.iterations() * days),
                                                    benchmark::Counter::kIsRate);
}

}  // namespace ecorail::bench
