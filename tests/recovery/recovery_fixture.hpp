// A small line for the delay-recovery tests: the reference train on A6 -> A9 (three sections),
// a plan that runs every section 20 s above its flat-out time with 30 s dwells, and frontiers
// of 30 s at 2 s steps kept in a cache in the build tree, so the test processes (one per test
// under ctest) compute each frontier once.
#pragma once

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "data/line_loader.hpp"
#include "data/route_builder.hpp"
#include "data/train_io.hpp"
#include "dp/section_library.hpp"
#include "output/frontier_cache.hpp"
#include "output/section_run_cache.hpp"
#include "recovery/plan.hpp"
#include "recovery/section_runs.hpp"

namespace ecorail::recovery::testing {

inline const std::vector<std::string>& small_stops() {
  static const std::vector<std::string> stops =
      data::stops_between(data::default_line(), "A6", "A9");
  return stops;
}

inline const dp::SectionLibrary& small_library() {
  static const std::unique_ptr<dp::SectionLibrary> lib = [] {
    const auto line = data::default_line();
    const auto train = data::default_train();
    dp::SectionLibraryOptions o;
    o.frontier_span_s = 30.0;
    o.frontier_step_s = 2.0;
    // The cache key names the line and train by their checksums, so a changed reference
    // line or train never reads a stale frontier.
    const std::string key = "recovery-tests|" + std::to_string(line.checksum()) + "|" +
                            std::to_string(data::train_checksum(train));
    return std::make_unique<dp::SectionLibrary>(
        train, data::build_routes(line, small_stops(), train), o, key);
  }();
  return *lib;
}

inline dp::FrontierStore* test_store() {
  static output::FileFrontierStore store(std::string(ECORAIL_BINARY_DIR) +
                                         "/test-cache/recovery-frontiers");
  return &store;
}

// The Monte Carlo's section runs of the small line, knots every 2 s (the frontier step), kept
// in the build tree's cache like the frontiers.
inline SectionRuns& small_runs() {
  static output::FileSectionRunStore store(std::string(ECORAIL_BINARY_DIR) +
                                           "/test-cache/recovery-section-runs");
  static SectionRuns runs(small_library(), test_store(), 2.0, 0.1, &store);
  return runs;
}

inline constexpr double kMargin_s = 20.0;  // planned running time above the flat-out run

// Trains departing A6 at `departures`, each section kMargin_s above its flat-out time (rounded
// to the millisecond), 30 s dwells.
inline Plan small_plan(const std::vector<double>& departures) {
  const dp::SectionLibrary& lib = small_library();
  std::vector<double> times;
  for (std::size_t k = 0; k < lib.size(); ++k)
    times.push_back(std::round((lib.min_time_s(k) + kMargin_s) * 1000.0) / 1000.0);
  return plan_from_pattern(small_stops(), times, {30.0, 30.0}, departures);
}

}  // namespace ecorail::recovery::testing
