// Every section of the reference line at every second of its frontier against an independent
// optimum (issue 24, item 5; docs/frontiers.md, "Against an independent search"). For each
// section the frontier (the single-section engine with its defaults, the minimum time + 1 s to
// + 60 s) and, at each point, the independent search of tests/dp/regime_search.hpp: "full
// traction, hold, coast, brake" with its two switch points searched on the simulator alone (no
// grid). The DP's energy is compared at the target time by its price (energy + lambda * (time
// - target): its run meets the time to 1 ms). A point below the search is no fault (the search
// spans one family of runs); a point above it by more than 0.01 % is one. Counters: points,
// points above the search by more than 0.01 % and 0.005 %, the largest excess (%). A line per
// point prints both energies. Arg: the section's index (0: A1 -> A2 ... 12: A13 -> A14). The
// search's points run on every core: A13 -> A14 alone took 268 s on 2 cores beside a build,
// the search over all 780 points 17.5 minutes (docs/frontiers.md).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "data/line_loader.hpp"
#include "data/route_builder.hpp"
#include "data/train_io.hpp"
#include "dp/frontier.hpp"
#include "dp/section_engine.hpp"
#include "physics/units.hpp"
#include "regime_search.hpp"

namespace {

using namespace ecorail;

void BM_SectionFamily(benchmark::State& state) {
  const physics::Train train = data::default_train();
  const data::Line line = data::default_line();
  const int arg = static_cast<int>(state.range(0));
  int points = 0, above_1e4 = 0, above_5e5 = 0;
  double worst_percent = -INFINITY;
  for (auto _ : state) {
    points = above_1e4 = above_5e5 = 0;
    worst_percent = -INFINITY;
    {
      const std::size_t i = static_cast<std::size_t>(arg);
      const std::string& from = line.stations[i].name;
      const std::string& to = line.stations[i + 1].name;
      const physics::Route route = data::build_route(line, from, to, train);
      const dp::SectionEngine engine(train, route, {});
      const dp::Frontier frontier = dp::compute_frontier(engine, {});
      std::vector<dp::FrontierPoint> priced;
      for (const dp::FrontierPoint& p : frontier.points) {
        if (p.lambda_J_per_s > 0.0 && p.target_time_s > frontier.min_time_s) priced.push_back(p);
      }
      const physics::SpeedEnvelope envelope(train, route);
      const physics::Motion motion(train, route, envelope);
      std::vector<double> family_J(priced.size());
#pragma omp parallel for schedule(dynamic)
      for (std::size_t k = 0; k < priced.size(); ++k) {
        family_J[k] = test::search_regimes(motion, priced[k].target_time_s, route.length_m(), 0.5)
                          .traction_energy_J;
      }
      for (std::size_t k = 0; k < priced.size(); ++k) {
        const dp::FrontierPoint& p = priced[k];
        const double at_target_J =
            p.traction_work_J + p.lambda_J_per_s * (p.running_time_s - p.target_time_s);
        const double percent = 100.0 * (at_target_J - family_J[k]) / family_J[k];
        std::printf("%s -> %s %.0f s: DP %.2f kJ (%.2f at the target), search %.2f kJ, %+.4f %%\n",
                    from.c_str(), to.c_str(), p.target_time_s, units::J_to_kJ(p.traction_work_J),
                    units::J_to_kJ(at_target_J), units::J_to_kJ(family_J[k]), percent);
        ++points;
        above_1e4 += percent > 0.01;
        above_5e5 += percent > 0.005;
        worst_percent = std::max(worst_percent, percent);
      }
    }
  }
  state.counters["points"] = points;
  state.counters["above_0.01%"] = above_1e4;
  state.counters["above_0.005%"] = above_5e5;
  state.counters["largest_excess_%"] = worst_percent;
}
BENCHMARK(BM_SectionFamily)
    ->DenseRange(0, 12)
    ->Iterations(1)
    ->Unit(benchmark::kSecond)
    ->UseRealTime();

}  // namespace
BENCHMARK_MAIN();
