// Random feasible timing-point journeys (dp/timing_journey.hpp), solved one after another: how
// many meet every window on their re-simulation, and how their traction energy compares with the
// witness run each journey was built around (a feasible run, so the optimum is no dearer). Each
// journey is built from a random witness on a 3 km track with a 6 per mille rise over
// 1000-1800 m (limit 80 km/h, the default train, --ds 10 --dv 0.5): full traction, a coast, then
// in each stretch between passing points a burst of traction and a coast or a hold and a coast;
// each passing point gets at random a time window of zero width at the witness's time, a latest
// or an earliest bound there, bounds a few seconds either side, a latest bound with a speed window
// around the witness's speed, or a zero-width time with a least speed; the stop the witness's
// time exactly or a 10 s window ending there. First arg 0: three passing points, at rest at the
// start; 1: the same with a moving start (1 to 6 m/s); 2: a moving start and zero-width windows
// only (each passing point pinned in time and speed, in time alone or in speed alone, the stop
// at the witness's time); second arg: the seed. 30 journeys each
// (docs/ttobench.md, "Random windows"). A journey that misses a window, or whose run is more
// than 0.1 % dearer than its witness, is printed to stderr with its windows and the solver's
// warnings; a solve over 20 s is named there with its evaluations.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <random>
#include <string>

#include "data/train_io.hpp"
#include "dp/section_engine.hpp"
#include "dp/time_target.hpp"
#include "dp/timing_journey.hpp"
#include "tests/dp/witness_runs.hpp"

namespace {

using ecorail::dp::TimingWindow;
namespace physics = ecorail::physics;
constexpr double kOpen = std::numeric_limits<double>::infinity();
constexpr double kLength_m = 3000.0;
constexpr int kPassingPoints = 3;
constexpr int kJourneys = 30;
constexpr double kSlowSolve_s = 20.0;  // a solve this long is named on stderr

physics::Route rise_track() {
  std::vector<physics::RouteSegment> segs(3);
  const double ends[] = {1000.0, 1800.0, kLength_m};
  double start = 0.0;
  for (int i = 0; i < 3; ++i) {
    segs[i].start_m = start;
    segs[i].end_m = ends[i];
    segs[i].gradient_permille = i == 1 ? 6.0 : 0.0;
    segs[i].speed_limit_ms = 80.0 / 3.6;
    start = ends[i];
  }
  return physics::Route(segs, 0.0, 1, "X0", "X1");
}

struct Journey {
  std::vector<TimingWindow> windows;
  double witness_J = 0.0;
  physics::SimulationResult witness_sim;
};

// A random journey around a random witness run (see the file's comment); false for a witness
// that does not reach the stop.
bool random_journey(const ecorail::dp::SectionEngine& engine, std::mt19937& rng, int mode,
                    Journey* out) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  ecorail::dp::timing_test::WitnessRun witness;
  if (!ecorail::dp::timing_test::random_witness(engine, rng, mode >= 1, kPassingPoints, &witness)) {
    return false;
  }
  const std::vector<double>& s = witness.points_m;
  const double v0 = witness.start_speed_ms;
  const physics::SimulationResult& w = witness.sim;
  out->witness_J = w.energy.traction_work_J;
  out->witness_sim = w;
  if (mode == 2) {
    out->windows = ecorail::dp::timing_test::zero_width_windows(witness, rng);
    return true;
  }
  out->windows = {{0.0, 0.0, 0.0, v0, v0}};
  for (int k = 0; k < kPassingPoints; ++k) {
    double t = NAN, v = NAN;
    ecorail::dp::timing_test::passing(w, s[k], &t, &v);
    TimingWindow pw{s[k], -kOpen, kOpen, -kOpen, kOpen};
    switch (std::uniform_int_distribution<int>(0, 5)(rng)) {
      case 0:
        pw.earliest_s = pw.latest_s = t;
        break;
      case 1:
        pw.latest_s = t;
        break;
      case 2:
        pw.earliest_s = t;
        break;
      case 3:
        pw.earliest_s = t - 3.0 * u(rng), pw.latest_s = t + 3.0 * u(rng);
        break;
      case 4:
        pw.latest_s = t;
        pw.min_speed_ms = v - 1.0 * u(rng), pw.max_speed_ms = v + 1.0 * u(rng);
        break;
      default:
        pw.earliest_s = pw.latest_s = t;
        pw.min_speed_ms = std::max(0.5, v - 2.0 * u(rng));
    }
    out->windows.push_back(pw);
  }
  const double arrive = w.running_time_s;
  out->windows.push_back({kLength_m, u(rng) < 0.5 ? arrive : arrive - 10.0, arrive, 0.0, 0.0});
  return true;
}

// The journey's windows, on stderr (after a line's head).
void print_journey(const Journey& j) {
  for (const TimingWindow& x : j.windows) {
    std::fprintf(stderr, " [%.1f m: %.3f, %.3f s, %.3f, %.3f m/s]", x.position_m, x.earliest_s,
                 x.latest_s, x.min_speed_ms, x.max_speed_ms);
  }
}

// One journey's solution against its witness, stretch by stretch between its windows (traction
// kJ, passing time and speed), and each part's program (from_m:control), on stderr.
void print_against_witness(const Journey& j, const ecorail::dp::TimingJourneySolution& sol,
                           double ratio, double took_s) {
  for (std::size_t k = 0; k + 1 < j.windows.size(); ++k) {
    const double a = j.windows[k].position_m, b = j.windows[k + 1].position_m;
    double witness_t_s = NAN, witness_v_ms = NAN;
    ecorail::dp::timing_test::passing(j.witness_sim, b, &witness_t_s, &witness_v_ms);
    double e = 0.0;  // each part's trace starts at 0 m
    for (std::size_t q = 0; q < sol.journey.sections.size() && q < sol.parts.size(); ++q) {
      const double off = sol.parts[q].start_m;
      e += ecorail::dp::timing_test::traction_work_between_J(sol.journey.sections[q].run.sim,
                                                             a - off, b - off);
    }
    std::fprintf(stderr,
                 "  %.1f-%.1f m: %.1f kJ (witness %.1f kJ), then %.3f s, %.3f m/s (witness %.3f s, "
                 "%.3f m/s)\n",
                 a, b, e / 1e3,
                 ecorail::dp::timing_test::traction_work_between_J(j.witness_sim, a, b) / 1e3,
                 sol.windows[k + 1].time_s, sol.windows[k + 1].speed_ms, witness_t_s, witness_v_ms);
  }
  for (std::size_t q = 0; q < sol.journey.sections.size(); ++q) {
    std::fprintf(stderr, "  part %zu:", q + 1);
    for (const physics::ProgramStep& st : sol.journey.sections[q].run.program) {
      std::fprintf(stderr, " %.1f:%d", st.from_m, static_cast<int>(st.control));
    }
    std::fprintf(stderr, "\n");
  }
  std::fprintf(stderr, "%.1f kJ, %.4f of its witness, %.1f s, %d evaluations\n",
               sol.summary.traction_energy_kJ, ratio, took_s, sol.summary.evaluations);
  for (const std::string& w : sol.summary.warnings) std::fprintf(stderr, "  %s\n", w.c_str());
}

// The bench's coarse grid: --ds 10 --dv 0.5 (substeps of 5 m).
ecorail::dp::TimingJourneyOptions coarse_options() {
  ecorail::dp::TimingJourneyOptions o;
  o.engine.grid.ds_m = 10.0;
  o.engine.grid.dv_kmh = 0.5;
  o.engine.grid.substep_m = 5.0;
  return o;
}

// The journeys are drawn with the coarse grid's engine (the same journeys whatever grid solves
// them) and solved with `solving`.
void run_random_windows(benchmark::State& state, const ecorail::dp::TimingJourneyOptions& solving) {
  const int mode = static_cast<int>(state.range(0));
  const physics::Train train = ecorail::data::default_train();
  const physics::Route track = rise_track();
  const ecorail::dp::SectionEngine engine(train, track, coarse_options().engine);
  int met = 0, missed = 0, dearer = 0;
  double worst_ratio = 0.0, slowest_s = 0.0;
  // ECORAIL_BENCH_JOURNEY=K solves only the sample's journey K (1-based; the others are still
  // drawn, so K is the same journey as in the whole sample's run) and prints its windows and its
  // solution against its witness stretch by stretch: where a dearer run loses its energy.
  const char* only_env = std::getenv("ECORAIL_BENCH_JOURNEY");
  const int only = only_env ? std::atoi(only_env) : 0;
  for (auto _ : state) {
    std::mt19937 rng(static_cast<unsigned>(state.range(1)));
    met = missed = dearer = 0;
    worst_ratio = slowest_s = 0.0;
    for (int made = 0; made < kJourneys;) {
      Journey j;
      if (!random_journey(engine, rng, mode, &j)) continue;
      ++made;
      if (only > 0 && made != only) continue;
      if (only > 0) {
        std::fprintf(stderr, "journey %d:", made);
        print_journey(j);
        std::fprintf(stderr, "\n");
      }
      const auto t0 = std::chrono::steady_clock::now();
      const ecorail::dp::TimingJourneySolution sol =
          ecorail::dp::solve_timing_journey(train, track, j.windows, solving);
      const double took_s =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      slowest_s = std::max(slowest_s, took_s);
      if (took_s > kSlowSolve_s) {
        std::fprintf(stderr, "slow (journey %d, %.1f s, %d evaluations)\n", made, took_s,
                     sol.summary.evaluations);
      }
      if (!sol.windows_met || !sol.summary.IsSolutionUsable()) {
        ++missed;
        std::fprintf(stderr, "missed (journey %d):", made);
        print_journey(j);
        for (const std::string& w : sol.summary.warnings) std::fprintf(stderr, "\n  %s", w.c_str());
        std::fprintf(stderr, "\n");
        continue;
      }
      ++met;
      const double ratio = sol.summary.traction_energy_kJ * 1e3 / j.witness_J;
      worst_ratio = std::max(worst_ratio, ratio);
      if (only > 0) print_against_witness(j, sol, ratio, took_s);
      if (ratio > 1.001) {
        ++dearer;
        std::fprintf(stderr, "dearer (journey %d, %.4f of its witness):", made, ratio);
        print_journey(j);
        for (const std::string& w : sol.summary.warnings) std::fprintf(stderr, "\n  %s", w.c_str());
        std::fprintf(stderr, "\n");
      }
    }
  }
  state.counters["journeys"] = kJourneys;
  state.counters["windows_met"] = met;
  state.counters["windows_missed"] = missed;
  state.counters["dearer_than_witness"] = dearer;
  state.counters["worst_energy_to_witness"] = worst_ratio;
  state.counters["slowest_solve_s"] = slowest_s;
}

void BM_RandomTimingWindows(benchmark::State& state) {
  run_random_windows(state, coarse_options());
}

// The same journeys' generator solved at the options `solve` uses by default (5 m x 0.2 km/h).
void BM_RandomTimingWindowsDefaultGrid(benchmark::State& state) {
  run_random_windows(state, ecorail::dp::TimingJourneyOptions{});
}
// {start, seed}: the first two samples are the ones the changes of docs/ttobench.md were made
// on, the next two were drawn after them (out of sample), the next two after the transition
// bands, the next two after the split phases, the last two (start 2: zero-width windows
// only) after the speed pins (docs/ttobench.md).
BENCHMARK(BM_RandomTimingWindows)
    ->Args({0, 2})
    ->Args({1, 3})
    ->Args({0, 11})
    ->Args({1, 12})
    ->Args({0, 21})
    ->Args({1, 22})
    ->Args({0, 31})
    ->Args({1, 32})
    ->Args({2, 41})
    ->Args({2, 42})
    ->Iterations(1)
    ->Unit(benchmark::kSecond);
// {start, seed} at the default grid: 51 and 52 were first run with a one-off copy of this bench
// (stop 43), 61 and 62 drawn on 2026-12-06; 71 and 72 zero-width windows only (start 2, drawn
// on 2026-12-06 after the speed pins, docs/ttobench.md, "One speed at a free time").
BENCHMARK(BM_RandomTimingWindowsDefaultGrid)
    ->Args({0, 51})
    ->Args({1, 52})
    ->Args({0, 61})
    ->Args({1, 62})
    ->Args({2, 71})
    ->Args({2, 72})
    ->Iterations(1)
    ->Unit(benchmark::kSecond);

}  // namespace

BENCHMARK_MAIN();
