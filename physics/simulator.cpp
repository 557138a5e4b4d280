#include "physics/simulator.hpp"

#include <algorithm>
#include <cmath>

namespace ecorail::physics {

namespace {
constexpr double kCreep_ms = 0.01;
}  // namespace

SimulationResult simulate(const Motion& motion, const ControlLaw& law,
                          const std::vector<double>& breakpoints_m, const SimulationOptions& opt) {
  const Route& route = motion.route();
  const Train& train = motion.train();
  const double length = route.length_m();
  std::vector<double> events = breakpoints_m;
  for (double p : route.change_points_m()) events.push_back(p);
  std::sort(events.begin(), events.end());

  SimulationResult out;
  double s = opt.start_position_m;
  double e = 0.5 * opt.start_speed_ms * opt.start_speed_ms;
  double t = 0.0;
  out.trace.reserve(static_cast<std::size_t>((length - s) / opt.step_m) + events.size() + 2);
  out.trace.push_back({0.0, s, opt.start_speed_ms, 0.0, 0.0, Regime::Coast});
  auto next_event = std::upper_bound(events.begin(), events.end(), s + 1e-9);

  while (s < length - 1e-9) {
    while (next_event != events.end() && *next_event <= s + 1e-9) ++next_event;
    double next = std::min(length, s + opt.step_m);
    if (next_event != events.end()) next = std::min(next, *next_event);
    if (length - next < 1e-6) next = length;  // no sliver step at the end
    const double v0 = speed_from_e(e);
    const Control c = law(s, v0);
    Substep sub;
    bool capped = false;
    if (opt.speed_cap) {
      // The cap is taken where and when the step ends: first at the end time the step would
      // have uncapped, then once more at the end time of the capped step.
      sub = motion.substep(s, e, next - s, c, opt.rk_order);
      for (int pass = 0; pass < 2; ++pass) {
        // A cap below a creeping speed counts as zero: landing at 3e-5 m/s would take hours
        // to cover the next step, which is standing, not running.
        double cap = opt.speed_cap(opt.start_clock_s + t + sub.time_s, next);
        if (cap < kCreep_ms) cap = 0.0;
        const double e_cap = cap < std::numeric_limits<double>::infinity() ? 0.5 * cap * cap : cap;
        if (!(sub.e_end > e_cap)) break;
        capped = true;
        sub = motion.substep(s, e, next - s, c, opt.rk_order, e_cap);
      }
      const bool held = sub.stopped && sub.length_m <= 0.0;
      if (held) {
        // Held at rest by the cap: wait, the clock running, until it lifts.
        const double cap_here = opt.speed_cap(opt.start_clock_s + t, next);
        const double e_free = std::max(0.0, motion.substep(s, e, next - s, c, opt.rk_order).e_end);
        if (e_free > 0.0 && cap_here < kCreep_ms && out.cap_wait_s < opt.max_wait_s) {
          t += opt.wait_step_s;
          out.cap_wait_s += opt.wait_step_s;
          out.trace.push_back({t, s, 0.0, 0.0, 0.0, Regime::PartialBrake});
          continue;
        }
      }
    } else {
      sub = motion.substep(s, e, next - s, c, opt.rk_order);
    }
    if (train.has_efficiency_maps()) {
      out.energy.add_measured(sub.traction_work_J, sub.brake_work_J, sub.traction_input_J,
                              sub.regen_J);
    } else {
      out.energy.add(sub.traction_work_J, sub.brake_work_J, sub.regen_brake_work_J,
                     train.traction_efficiency, train.regen_efficiency);
    }
    t += sub.time_s;
    s = sub.stopped ? s + sub.length_m : next;  // exact positions: no drift over many steps
    e = sub.e_end;
    const double v1 = speed_from_e(e);
    const double accel = sub.time_s > 0.0 ? (v1 - v0) / sub.time_s : 0.0;
    out.trace.push_back({t, s, v1, accel, sub.mean_force_N, sub.regime});
    out.max_overspeed_ms =
        std::max(out.max_overspeed_ms, v1 - motion.envelope().static_limit_ms(s));
    if (opt.speed_cap) {
      out.max_cap_overspeed_ms =
          std::max(out.max_cap_overspeed_ms, v1 - opt.speed_cap(opt.start_clock_s + t, s));
      if (capped) out.cap_binding_m += sub.length_m;
    }
    if (sub.stopped) {
      out.stopped_early = s < length - kArrivalSlack_m;
      break;
    }
  }
  out.running_time_s = t;
  out.end_position_m = s;
  out.end_speed_ms = speed_from_e(e);
  if (out.end_speed_ms > 0.0) {
    // Still moving at the end: the stop error is where full braking would bring it to rest.
    const RouteSegment& last = route.segments().back();
    double ee = e;
    double extra = 0.0;
    const double h = 1e-3;
    while (ee > 0.0 && extra < 1e4) {
      const double v = speed_from_e(ee);
      const double w = train.resistance_N(v, last.track_N_per_kN());
      const double slope = (-train.max_brake_N(v, w) - w) / train.effective_mass_kg();
      if (ee + h * slope <= 0.0) {
        extra += ee / -slope;
        break;
      }
      ee += h * slope;
      extra += h;
    }
    out.end_position_m = length + extra;
  }
  out.stop_error_m = out.end_position_m - length;
  return out;
}

SimulationResult simulate(const Motion& motion, const ControlProgram& program,
                          const SimulationOptions& opt) {
  std::vector<double> breakpoints;
  for (const auto& step : program) breakpoints.push_back(step.from_m);
  // The entry holding s: the one found last time or the next (a cursor, as the run moves
  // forward), else a binary search; either gives the same entry.
  std::size_t cursor = 0;
  const ControlLaw law = [&program, &cursor](double s_m, double) {
    const double x = s_m + 1e-9;
    const std::size_t n = program.size();
    for (std::size_t k = cursor; k < n && k <= cursor + 1; ++k) {
      if (!(x < program[k].from_m) && (k + 1 == n || x < program[k + 1].from_m)) {
        cursor = k;
        return program[k].control;
      }
    }
    auto it = std::upper_bound(program.begin(), program.end(), x,
                               [](double s, const ProgramStep& p) { return s < p.from_m; });
    if (it != program.begin()) cursor = static_cast<std::size_t>(it - program.begin()) - 1;
    return it == program.begin() ? program.front().control : (it - 1)->control;
  };
  return simulate(motion, law, breakpoints, opt);
}

}  // namespace ecorail::physics
