// Example 01: the least-energy run of one section for a running time.
// Loads the reference line and train, solves A6 -> A7 in 110 s, and prints the summary, the
// regimes and the figures of the re-simulated run. Exits non-zero if the run misses the
// acceptance bounds (time within 0.1 s, stop within 0.5 m, no overspeed).
#include <cmath>
#include <cstdio>
#include <iostream>

#include "data/line_loader.hpp"
#include "data/route_builder.hpp"
#include "data/train_io.hpp"
#include "dp/section_solve.hpp"
#include "physics/units.hpp"

int main() {
  using namespace ecorail;
  const physics::Train train = data::default_train();
  const physics::Route route = data::build_route(data::default_line(), "A6", "A7", train);

  dp::SectionSolveOptions options;  // default grid: 5 m x 0.2 km/h
  const dp::SectionSolution solution = dp::solve_section(train, route, 110.0, options);

  std::cout << solution.summary.FullReport();
  for (const auto& r : solution.regimes) {
    std::printf("  %-16s %8.1f -> %8.1f m  %5.1f -> %5.1f km/h\n",
                std::string(physics::regime_name(r.regime)).c_str(), r.start_m, r.end_m,
                units::ms_to_kmh(r.start_speed_ms), units::ms_to_kmh(r.end_speed_ms));
  }
  const auto& sim = solution.run.sim;
  const bool ok = std::abs(sim.running_time_s - 110.0) <= 0.1 &&
                  std::abs(sim.stop_error_m) <= 0.5 && sim.max_overspeed_ms <= 0.05 / 3.6;
  return ok ? 0 : 1;
}
