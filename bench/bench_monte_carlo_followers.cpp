// Speed of the Monte Carlo days with driven followers (question 3.2): simulated service days per
// second of a day plan (the 240-train 2.2 day of docs/delays.md, given as $ECORAIL_DAY_CSV) with
// the followers driven by the follower model of `ecorail delay` (the default of `ecorail
// montecarlo`) and in the fast mode (--followers shortcut), exact recovery, on 1 and 2 threads.
// Everything made once per plan (frontiers, section runs, the followers' runs with their
// trajectories) is made before the timings, in the user's frontier cache (as `ecorail
// montecarlo` keys it, so a run of the command warms it). bench/montecarlo_followers.sh makes
// the day plan and runs this.
// Run: ECORAIL_DAY_CSV=day.csv build/bench/bench_monte_carlo_followers --benchmark_min_time=5
#include <benchmark/benchmark.h>

#include <cstdio>
#include <cstdlib>
#include <memory>

#include "data/line_loader.hpp"
#include "data/train_io.hpp"
#include "monte_carlo_days.hpp"
#include "output/frontier_cache.hpp"
#include "recovery/monte_carlo.hpp"
#include "recovery/plan_source.hpp"

namespace {

using namespace ecorail;

struct Setup : bench::DaysSetup {
  std::unique_ptr<recovery::MonteCarlo> driven, shortcut;
};

Setup& setup() {
  static Setup s = [] {
    Setup x;
    const char* csv = std::getenv("ECORAIL_DAY_CSV");
    if (csv == nullptr || *csv == 0) {
      std::fprintf(stderr, "set ECORAIL_DAY_CSV to a day plan (bench/montecarlo_followers.sh)\n");
      std::exit(2);
    }
    const auto line = data::default_line();
    const auto train = data::default_train();
    recovery::PlanStops ps = recovery::read_plan_stops(line, csv);
    x.plan = ps.plan;
    x.library = recovery::plan_section_library(line, train, ps.stops, dp::SectionLibraryOptions{});
    x.make_runs(output::FileFrontierStore::default_directory());
    recovery::MonteCarloOptions o;
    x.driven = std::make_unique<recovery::MonteCarlo>(*x.library, x.plan, o, *x.runs);
    o.followers = recovery::FollowerModel::Shortcut;
    x.shortcut = std::make_unique<recovery::MonteCarlo>(*x.library, x.plan, o, *x.runs);
    return x;
  }();
  return s;
}

void BM_DrivenFollowerDays(benchmark::State& state) {
  bench::time_days(state, *setup().driven, 4);
}
void BM_ShortcutFollowerDays(benchmark::State& state) {
  bench::time_days(state, *setup().shortcut, 4);
}

BENCHMARK(BM_DrivenFollowerDays)->Arg(1)->Arg(2)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ShortcutFollowerDays)->Arg(1)->Arg(2)->UseRealTime()->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
