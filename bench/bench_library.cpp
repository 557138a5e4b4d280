// Speed of the section library on the reference line: building every section's engine (cold),
// the whole library of 13 sections with their default frontiers (60 s span, 1 s step) cold and
// again from the file cache (output::FileFrontierStore in a temporary directory), the full-line
// journey A1 -> A14 in 1726 s (30 s dwells) on a library already built (against the same journey
// built from scratch, as `ecorail solve` does it, in the same run), frontiers served from a
// store, and binning one trip's power at 0.01 s. 2 threads (EngineOptions::threads) unless
// stated. Run: build/bench/bench_library --benchmark_min_time=1
#include <benchmark/benchmark.h>
#include <omp.h>

#include <unistd.h>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <string>

#include "data/line_loader.hpp"
#include "data/route_builder.hpp"
#include "data/train_io.hpp"
#include "dp/journey.hpp"
#include "dp/section_library.hpp"
#include "output/frontier_cache.hpp"

namespace {

using namespace ecorail;

struct Line {
  physics::Train train = data::default_train();
  std::vector<physics::Route> routes;
  Line() {
    const data::Line line = data::default_line();
    for (std::size_t i = 0; i + 1 < line.stations.size(); ++i) {
      routes.push_back(
          data::build_route(line, line.stations[i].name, line.stations[i + 1].name, train));
    }
  }
};

const Line& line() {
  static const Line l;
  return l;
}

void BM_LibraryBuildAllEngines(benchmark::State& state) {
  omp_set_num_threads(static_cast<int>(state.range(0)));
  for (auto _ : state) {
    const dp::SectionLibrary library(line().train, line().routes, {});
    library.build_engines(0, library.size());
    benchmark::DoNotOptimize(library.engine_builds());
  }
}
BENCHMARK(BM_LibraryBuildAllEngines)->Arg(2)->Unit(benchmark::kMillisecond);

// The whole library, cold: every engine and every default frontier, each frontier written to
// the file cache (a fresh directory per iteration, so nothing is read back).
// Google Benchmark may call a benchmark function more than once (to size its iterations), so
// the directory is removed when the program ends, not when a function returns.
std::filesystem::path bench_cache_dir() {
  static const std::filesystem::path dir = [] {
    std::atexit([] {
      std::error_code ec;
      std::filesystem::remove_all(std::filesystem::temp_directory_path() /
                                      ("ecorail-bench-frontiers-" + std::to_string(::getpid())),
                                  ec);
    });
    return std::filesystem::temp_directory_path() /
           ("ecorail-bench-frontiers-" + std::to_string(::getpid()));
  }();
  return dir;
}

dp::SectionLibraryOptions two_threads() {
  dp::SectionLibraryOptions o;
  o.engine.threads = 2;
  return o;
}

void BM_LibraryBuildAllFrontiersCold(benchmark::State& state) {
  for (auto _ : state) {
    state.PauseTiming();
    std::filesystem::remove_all(bench_cache_dir());
    output::FileFrontierStore cache(bench_cache_dir());
    state.ResumeTiming();
    const dp::SectionLibrary library(line().train, line().routes, two_threads());
    library.build_frontiers(0, library.size(), &cache);
    state.counters["frontier_computations"] = library.frontier_computations();
  }
}
BENCHMARK(BM_LibraryBuildAllFrontiersCold)->Iterations(1)->Unit(benchmark::kSecond);

// The same library from the cache the cold build wrote: engines are not built at all (a frontier
// read back needs none), every frontier is read and checked.
void BM_LibraryBuildAllFrontiersFromFileCache(benchmark::State& state) {
  output::FileFrontierStore cache(bench_cache_dir());
  {
    const dp::SectionLibrary fill(line().train, line().routes, two_threads());
    fill.build_frontiers(0, fill.size(), &cache);  // a no-op read when the cold run wrote it
  }
  for (auto _ : state) {
    const dp::SectionLibrary library(line().train, line().routes, two_threads());
    library.build_frontiers(0, library.size(), &cache);
    if (library.frontier_computations() != 0) state.SkipWithError("a frontier was recomputed");
    state.counters["frontier_loads"] = library.frontier_loads();
    state.counters["engine_builds"] = library.engine_builds();
  }
}
BENCHMARK(BM_LibraryBuildAllFrontiersFromFileCache)->Unit(benchmark::kMillisecond);

dp::JourneyOptions journey_options() {
  dp::JourneyOptions o;
  o.measure_marginals = false;  // as `ecorail solve` for more than 4 sections
  return o;
}

void BM_FullLineJourneyOnBuiltLibrary(benchmark::State& state) {
  omp_set_num_threads(2);
  const dp::SectionLibrary library(line().train, line().routes, {});
  library.build_engines(0, library.size());
  const std::vector<double> dwells(line().routes.size() - 1, 30.0);
  for (auto _ : state) {
    const dp::JourneySolution s =
        dp::solve_journey(library, 0, library.size(), dwells, 1726.0, journey_options());
    benchmark::DoNotOptimize(s.traction_work_J);
  }
  state.counters["engine_builds"] = library.engine_builds();  // stays 13
}
BENCHMARK(BM_FullLineJourneyOnBuiltLibrary)->Unit(benchmark::kMillisecond);

// The same with every frontier in the library (as served from the cache): the frontiers give
// the price search its starting point.
void BM_FullLineJourneyOnLibraryWithFrontiers(benchmark::State& state) {
  omp_set_num_threads(2);
  dp::SectionLibraryOptions options;
  options.frontier_span_s = 40.0;
  const dp::SectionLibrary library(line().train, line().routes, options);
  library.build_frontiers(0, library.size(), nullptr);
  const std::vector<double> dwells(line().routes.size() - 1, 30.0);
  int evaluations = 0;
  for (auto _ : state) {
    const dp::JourneySolution s =
        dp::solve_journey(library, 0, library.size(), dwells, 1726.0, journey_options());
    evaluations = s.lambda_evaluations;
    benchmark::DoNotOptimize(s.traction_work_J);
  }
  state.counters["lambda_evaluations"] = evaluations;
}
BENCHMARK(BM_FullLineJourneyOnLibraryWithFrontiers)->Unit(benchmark::kMillisecond);

void BM_FullLineJourneyFromScratch(benchmark::State& state) {
  omp_set_num_threads(2);
  const std::vector<double> dwells(line().routes.size() - 1, 30.0);
  for (auto _ : state) {
    const dp::JourneySolution s =
        dp::solve_journey(line().train, line().routes, dwells, 1726.0, journey_options());
    benchmark::DoNotOptimize(s.traction_work_J);
  }
}
BENCHMARK(BM_FullLineJourneyFromScratch)->Unit(benchmark::kMillisecond);

class MemoryStore : public dp::FrontierStore {
 public:
  std::optional<dp::Frontier> load(const std::string& key) override {
    auto it = entries.find(key);
    return it == entries.end() ? std::nullopt : std::optional<dp::Frontier>(it->second);
  }
  void save(const std::string& key, const dp::Frontier& f) override { entries[key] = f; }
  std::map<std::string, dp::Frontier> entries;
};

void BM_LibraryFrontiersFromStore(benchmark::State& state) {
  omp_set_num_threads(2);
  dp::SectionLibraryOptions options;
  options.frontier_span_s = 10.0;
  options.frontier_step_s = 2.0;
  MemoryStore store;
  {
    const dp::SectionLibrary cold(line().train, line().routes, options);
    cold.build_frontiers(0, cold.size(), &store);
  }
  for (auto _ : state) {
    const dp::SectionLibrary warm(line().train, line().routes, options);
    for (std::size_t i = 0; i < warm.size(); ++i) {
      benchmark::DoNotOptimize(warm.frontier(i, &store).t_max_s());
    }
    if (warm.frontier_computations() != 0) state.SkipWithError("a frontier was recomputed");
  }
}
BENCHMARK(BM_LibraryFrontiersFromStore)->Unit(benchmark::kMicrosecond);

void BM_PowerBinsOfOneTripAt10ms(benchmark::State& state) {
  omp_set_num_threads(2);
  const dp::SectionLibrary library(line().train, line().routes, {});
  const std::vector<double> dwells(line().routes.size() - 1, 30.0);
  const dp::JourneySolution s =
      dp::solve_journey(library, 0, library.size(), dwells, 1726.0, journey_options());
  std::vector<physics::TripSection> sections;
  for (std::size_t i = 0; i < s.sections.size(); ++i) {
    sections.push_back({&library.route(i), &s.sections[i].run.sim, s.sections[i].dwell_after_s});
  }
  const physics::Trip trip(sections, 0.0, line().train.regen_efficiency);
  for (auto _ : state) {
    const physics::PowerBins bins = trip.power_bins(0.01);
    benchmark::DoNotOptimize(bins.traction_W.data());
  }
  state.counters["samples"] = static_cast<double>(trip.samples().size());
}
BENCHMARK(BM_PowerBinsOfOneTripAt10ms)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
