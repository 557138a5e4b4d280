// What the Monte Carlo benchmarks share: the setup made once outside the timings (a line's
// section library, its plan and the section runs, kept in a cache directory) and the timing
// loop: each iteration runs the next `days` days of mc (never the same days twice, so no day is
// answered from a cache) on state.range(0) threads, and the counter days_per_s is simulated
// days per second of wall time.
#pragma once

#include <benchmark/benchmark.h>

#include <cstdint>
#include <filesystem>
#include <memory>

#include "output/frontier_cache.hpp"
#include "output/section_run_cache.hpp"
#include "recovery/monte_carlo.hpp"

namespace ecorail::bench {

// A benchmark's section library and plan (filled by the benchmark), and the section runs that
// make_runs makes from them.
struct DaysSetup {
  std::unique_ptr<dp::SectionLibrary> library;
  recovery::Plan plan;
  std::unique_ptr<output::FileFrontierStore> frontiers;
  std::unique_ptr<output::FileSectionRunStore> store;
  std::unique_ptr<recovery::SectionRuns> runs;

  // The section runs of the library (knots every 1 s, 0.1 s power bins, as `ecorail montecarlo`
  // makes them), frontiers and runs kept in dir as `ecorail montecarlo --cache-dir` keeps them.
  void make_runs(const std::filesystem::path& dir) {
    frontiers = std::make_unique<output::FileFrontierStore>(dir);
    store = std::make_unique<output::FileSectionRunStore>(dir / "section-runs");
    runs =
        std::make_unique<recovery::SectionRuns>(*library, frontiers.get(), 1.0, 0.1, store.get());
  }
};

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
