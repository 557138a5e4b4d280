// What departures at fractions of a second would add (docs/fleet.md, "Whole seconds"). ecorail's
// timetables depart at whole seconds (the problem, the CSV, GTFS and the bounds are stated so);
// the power-flow model itself steps 0.01 s. This program takes the optimiser's whole-second
// result with its defaults (seed 1) and then climbs on the model's own step: every train but the
// first and the last, in turn, goes to the departure within a window of its current one (0.5 s
// in the first sweep, 0.05 s after it) that uses the most regenerated energy, its headways kept
// in their class, until a sweep moves no train. The used energy is summed exactly in
// micro-joules on the model's bins (the same integers the model uses), so the climb never loses.
//   Arg 0: question 2.1 (100 trains, the optimiser's defaults, no time limit).
//   Arg 1: question 2.2's day (240 trains, peaks 7200-12600 s and 43200-50400 s at 120-150 s,
//          off-peak 300-660 s, the optimiser with a 60 s limit).
// Counters: the whole-second result's and the climb's used energy and fraction of the
// regeneration, and the sweeps; a line per question prints the energies to 0.1 kJ. Run:
// build/bench/bench_sub_second (about 4 minutes on 2 cores).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <vector>

#include "energy/power_flow_model.hpp"
#include "fleet/fleet_pattern.hpp"
#include "fleet/fleet_problem.hpp"
#include "fleet/headway_optimiser.hpp"
#include "reference_pattern.hpp"

namespace {

using namespace ecorail;

fleet::FleetProblem problem_of(int question) {
  fleet::FleetProblem p;
  if (question == 1) {
    p.trains = 240;
    p.headway_min_s = 300;
    p.peak_windows = {{7200, 12600}, {43200, 50400}};
  }
  return p;
}

// The fleet's power on the model's bins, one train laid or lifted at a time.
class TickBalance {
 public:
  TickBalance(const energy::PowerProfile& profile, long last_departure_ticks)
      : traction_(profile.dense_traction()),
        regen_(profile.dense_regen()),
        span_(profile.span_bins()),
        r_(static_cast<std::size_t>(last_departure_ticks + span_ + 1), 0),
        t_(r_.size(), 0) {}
  void lay(long departure, int sign) {
    for (long b = 0; b < span_; ++b) {
      r_[departure + b] += sign * regen_[b];
      t_[departure + b] += sign * traction_[b];
    }
  }
  // What laying a train at `departure` would add to the used energy.
  std::int64_t gain_at(long departure) const {
    std::int64_t gain = 0;
    for (long b = 0; b < span_; ++b) {
      const std::int64_t r = r_[departure + b], t = t_[departure + b];
      gain += std::min(r + regen_[b], t + traction_[b]) - std::min(r, t);
    }
    return gain;
  }
  std::int64_t used() const {
    std::int64_t u = 0;
    for (std::size_t i = 0; i < r_.size(); ++i) u += std::min(r_[i], t_[i]);
    return u;
  }

 private:
  const std::vector<energy::MicroJoules>& traction_;
  const std::vector<energy::MicroJoules>& regen_;
  long span_;
  std::vector<std::int64_t> r_, t_;
};

// Whether a train may depart at b ticks after one at a (the problem's class by the clock).
bool allowed(const fleet::FleetProblem& p, long a, long b, long tps) {
  bool peak = false;
  for (const fleet::PeakWindow& w : p.peak_windows)
    peak = peak || (a < w.to_s * tps && b > w.from_s * tps);
  const long lo = peak ? p.peak_headway_min_s : p.headway_min_s;
  const long hi = peak ? p.peak_headway_max_s : p.headway_max_s;
  return b - a >= lo * tps && b - a <= hi * tps;
}

void BM_SubSecondDepartures(benchmark::State& state) {
  const fleet::FleetProblem problem = problem_of(static_cast<int>(state.range(0)));
  const fleet::PatternTrip& pattern = bench::reference_pattern();
  const energy::PowerFlowModel model(pattern.trip, fleet::limits_of(problem),
                                     energy::EnergyModelOptions{});
  fleet::HeadwayOptimiserOptions options;
  if (problem.windowed()) options.time_limit_s = 60.0;
  const energy::PowerProfile& profile = model.profile();
  const long tps = profile.ticks_per_second();
  const double regen_J = energy::to_joules(profile.regen_total()) * problem.trains;
  for (auto _ : state) {
    const fleet::HeadwayOptimiserResult whole = fleet::optimise_headways(model, problem, options);
    std::vector<long> dep;
    for (int d : fleet::departures_from_headways(whole.headways_s)) dep.push_back(d * tps);
    TickBalance balance(profile, dep.back());
    for (long d : dep) balance.lay(d, 1);
    const long n = static_cast<long>(dep.size());
    int sweeps = 0;
    for (long moved = 1; moved > 0 && sweeps < 1000; ++sweeps) {
      moved = 0;
      const long window = sweeps == 0 ? tps / 2 : std::max(1L, tps / 20);
      for (long i = 1; i + 1 < n; ++i) {
        balance.lay(dep[i], -1);
        std::int64_t best = balance.gain_at(dep[i]);
        long arg = dep[i];
        for (long d = dep[i] - window; d <= dep[i] + window; ++d) {
          if (d == dep[i] || !allowed(problem, dep[i - 1], d, tps) ||
              !allowed(problem, d, dep[i + 1], tps))
            continue;
          const std::int64_t gain = balance.gain_at(d);
          if (gain > best) best = gain, arg = d;
        }
        moved += arg != dep[i];
        dep[i] = arg;
        balance.lay(dep[i], 1);
      }
    }
    const double used_J = energy::to_joules(balance.used());
    state.counters["whole_second_used_kJ"] = whole.summary.used_regen_J / 1e3;
    state.counters["whole_second_fraction"] = whole.summary.used_regen_J / regen_J;
    state.counters["sub_second_used_kJ"] = used_J / 1e3;
    state.counters["sub_second_fraction"] = used_J / regen_J;
    state.counters["sweeps"] = sweeps;
    // The counters print six digits; the energies to 0.1 kJ:
    std::printf(
        "question 2.%ld: whole seconds %.1f kJ (%.6f), on the model's step %.1f kJ (%.6f)\n",
        state.range(0) + 1, whole.summary.used_regen_J / 1e3, whole.summary.used_regen_J / regen_J,
        used_J / 1e3, used_J / regen_J);
  }
}
BENCHMARK(BM_SubSecondDepartures)->Arg(0)->Arg(1)->Unit(benchmark::kSecond)->Iterations(1);

}  // namespace

BENCHMARK_MAIN();
