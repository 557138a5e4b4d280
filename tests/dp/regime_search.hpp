// An independent optimiser for the tests: searches the switching points of the classic
// energy-saving strategy "full traction, optional speed hold, coast, full brake" with the
// physics simulator alone (no grid, no value function). For a hold length, the end of full
// traction is bisected until the re-simulated running time meets the target; the energy is
// then minimised over the hold length by a scan and a golden-section refinement. The final
// braking comes from the speed envelope (the train brakes when it meets the braking curve).
#pragma once

#include <cmath>
#include <functional>

#include "physics/simulator.hpp"

namespace ecorail::test {

// Whether a run brakes in a step that ends by to_m, the step that ends there included (a run
// a little too fast at a lower limit's start is capped by its braking curve in that step
// alone): the families' coast into a lower limit starts as late as it can without it.
inline bool brakes_by(const physics::SimulationResult& sim, double to_m) {
  for (const auto& p : sim.trace) {
    if (p.s_m > to_m + 1e-6) break;
    if (p.regime == physics::Regime::FullBrake || p.regime == physics::Regime::PartialBrake)
      return true;
  }
  return false;
}

struct RegimeSearchResult {
  double traction_energy_J = 0.0;
  double running_time_s = 0.0;
  double traction_end_m = 0.0;
  double hold_length_m = 0.0;
};

inline physics::SimulationResult run_strategy(const physics::Motion& motion, double x1, double hold,
                                              double step_m) {
  physics::SimulationOptions opt;
  opt.step_m = step_m;
  physics::ControlProgram program = {{0.0, physics::Control::MaxTraction},
                                     {x1, physics::Control::Hold},
                                     {x1 + hold, physics::Control::Coast}};
  return physics::simulate(motion, program, opt);
}

// Running time, counting a run that comes to rest before the station as infinitely slow.
inline double strategy_time(const physics::Motion& motion, double x1, double hold, double step_m) {
  const auto sim = run_strategy(motion, x1, hold, step_m);
  return sim.stopped_early ? INFINITY : sim.running_time_s;
}

// Energy of the strategy with this hold length that meets the target time (infinite if none).
inline double energy_for_hold(const physics::Motion& motion, double target_s, double hold,
                              double step_m, double* x1_out) {
  const double length = motion.route().length_m();
  double lo = 1.0, hi = length - hold - 1.0;
  if (hi <= lo) return INFINITY;
  if (strategy_time(motion, hi, hold, step_m) > target_s) return INFINITY;
  if (strategy_time(motion, lo, hold, step_m) < target_s) return INFINITY;
  for (int it = 0; it < 34; ++it) {  // 1354 m / 2^34: well below a micrometre
    const double mid = 0.5 * (lo + hi);
    (strategy_time(motion, mid, hold, step_m) > target_s ? lo : hi) = mid;
  }
  *x1_out = hi;
  return run_strategy(motion, hi, hold, step_m).energy.traction_work_J;
}

inline RegimeSearchResult search_regimes(const physics::Motion& motion, double target_s,
                                         double max_hold_m, double step_m = 0.25) {
  // Scan hold lengths, then refine the best bracket by golden section.
  double best_hold = 0.0, best_e = INFINITY, x1 = 0.0;
  const double scan_step = 25.0;
  for (double hold = 0.0; hold <= max_hold_m; hold += scan_step) {
    const double e = energy_for_hold(motion, target_s, hold, step_m, &x1);
    if (e < best_e) {
      best_e = e;
      best_hold = hold;
    }
  }
  double a = std::max(0.0, best_hold - scan_step), b = best_hold + scan_step;
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  double c = b - g * (b - a), d = a + g * (b - a);
  double fc = energy_for_hold(motion, target_s, c, step_m, &x1);
  double fd = energy_for_hold(motion, target_s, d, step_m, &x1);
  for (int it = 0; it < 16; ++it) {
    if (fc < fd) {
      b = d, d = c, fd = fc;
      c = b - g * (b - a);
      fc = energy_for_hold(motion, target_s, c, step_m, &x1);
    } else {
      a = c, c = d, fc = fd;
      d = a + g * (b - a);
      fd = energy_for_hold(motion, target_s, d, step_m, &x1);
    }
  }
  // Final evaluation at the engine's re-simulation step (0.05 m), re-bisected at that step, of
  // the better of the refined hold and the plain "traction, coast, brake" strategy.
  RegimeSearchResult r;
  r.traction_energy_J = INFINITY;
  for (double hold : {fc < fd ? c : d, 0.0}) {
    double x = 0.0;
    const double e = energy_for_hold(motion, target_s, hold, 0.05, &x);
    if (e < r.traction_energy_J) {
      r.traction_energy_J = e;
      r.traction_end_m = x;
      r.hold_length_m = hold;
    }
  }
  if (std::isfinite(r.traction_energy_J)) {
    r.running_time_s = run_strategy(motion, r.traction_end_m, r.hold_length_m, 0.05).running_time_s;
  }
  return r;
}

}  // namespace ecorail::test
