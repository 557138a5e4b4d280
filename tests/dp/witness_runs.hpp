// Random witness runs for timing-point journeys: a feasible run a random journey is built
// around (its windows at the run's passing times and speeds), so the journey's optimum is no
// dearer than the witness. Shared by bench/bench_timing_windows.cpp and the tests, so that a
// journey the bench prints can be rebuilt in a test from the same seed.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "dp/section_engine.hpp"
#include "dp/time_target.hpp"
#include "physics/simulator.hpp"
#include "physics/timing_window.hpp"

namespace ecorail::dp::timing_test {

struct WitnessRun {
  std::vector<double> points_m;  // the passing points, ascending
  double start_speed_ms = 0.0;
  double length_m = 0.0;          // the route's, where the run stops
  physics::SimulationResult sim;  // at a 1 m step on the engine's route, to rest at its end
};

// Full traction, a coast, then in each stretch between passing points a burst of traction and a
// coast or a hold and a coast; `points` passing points spread over the route; a moving start
// (1 to 6 m/s) when moving. The draws from rng are the same whatever the outcome; false for a
// program whose switches do not ascend, or a run that does not reach the stop.
inline bool random_witness(const SectionEngine& engine, std::mt19937& rng, bool moving, int points,
                           WitnessRun* out) {
  const double length_m = engine.route().length_m();
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<double> s;
  for (int k = 0; k < points; ++k) s.push_back(length_m * (k + 0.2 + 0.6 * u(rng)) / (points + 1));
  const double v0 = moving ? 1.0 + 5.0 * u(rng) : 0.0;
  physics::ControlProgram p = {{0.0, physics::Control::MaxTraction},
                               {(0.3 + 0.5 * u(rng)) * s[0], physics::Control::Coast}};
  for (int k = 0; k < points; ++k) {
    const double a = s[k], b = k + 1 < points ? s[k + 1] : length_m;
    const double y = a + (0.1 + 0.4 * u(rng)) * (b - a);
    p.push_back({y, physics::Control::MaxTraction});
    const bool hold = u(rng) < 0.5;
    p.push_back(
        {y + 30.0 + 80.0 * u(rng), hold ? physics::Control::Hold : physics::Control::Coast});
    if (hold) p.push_back({y + 150.0 + 100.0 * u(rng), physics::Control::Coast});
  }
  for (std::size_t i = 1; i < p.size(); ++i) {
    if (!(p[i].from_m > p[i - 1].from_m)) return false;
  }
  if (p.back().from_m >= length_m - 50.0) return false;
  out->points_m = s;
  out->start_speed_ms = v0;
  out->length_m = length_m;
  out->sim = engine.simulate(p, {0.0, v0}, 1.0);
  return run_arrives(out->sim);
}

// Time and speed where a run passes s_m (linear between trace points; NaN if it never does).
inline void passing(const physics::SimulationResult& sim, double s_m, double* t_s, double* v_ms) {
  *t_s = *v_ms = NAN;
  const auto& tr = sim.trace;
  for (std::size_t k = 1; k < tr.size(); ++k) {
    if (tr[k].s_m < s_m) continue;
    const double w = (s_m - tr[k - 1].s_m) / (tr[k].s_m - tr[k - 1].s_m);
    *t_s = tr[k - 1].t_s + w * (tr[k].t_s - tr[k - 1].t_s);
    *v_ms = tr[k - 1].v_ms + w * (tr[k].v_ms - tr[k - 1].v_ms);
    return;
  }
}

// Traction work of a run between two of its positions (J): its trace's positive force over
// each step, the steps cut at the ends.
inline double traction_work_between_J(const physics::SimulationResult& sim, double from_m,
                                      double to_m) {
  double work = 0.0;
  for (std::size_t i = 1; i < sim.trace.size(); ++i) {
    const double from = std::max(sim.trace[i - 1].s_m, from_m);
    const double to = std::min(sim.trace[i].s_m, to_m);
    if (to > from) work += std::max(0.0, sim.trace[i].force_N) * (to - from);
  }
  return work;
}

// Zero-width windows around a witness (bench/bench_timing_windows.cpp's start 2): its start
// speed at 0 m, each passing point at random pinned in time and speed, in time alone or in
// speed alone, and the stop at the witness's time.
inline std::vector<physics::TimingWindow> zero_width_windows(const WitnessRun& witness,
                                                             std::mt19937& rng) {
  const double open = std::numeric_limits<double>::infinity();
  const double v0 = witness.start_speed_ms;
  std::vector<physics::TimingWindow> windows = {{0.0, 0.0, 0.0, v0, v0}};
  for (const double s : witness.points_m) {
    double t = NAN, v = NAN;
    passing(witness.sim, s, &t, &v);
    switch (std::uniform_int_distribution<int>(0, 2)(rng)) {
      case 0:
        windows.push_back({s, t, t, v, v});
        break;
      case 1:
        windows.push_back({s, t, t, -open, open});
        break;
      default:
        windows.push_back({s, -open, open, v, v});
    }
  }
  const double arrive = witness.sim.running_time_s;
  windows.push_back({witness.length_m, arrive, arrive, 0.0, 0.0});
  return windows;
}

}  // namespace ecorail::dp::timing_test
