#include "physics/simulator.hpp"

#include <algorithm>
#include <cmath>

namespace ecorail::physics {

namespace {
constexpr double kCreep_ms = 0.01;

// A program as a law: the entry holding s is the one found last time or the next (a cursor,
// as the run moves forward), else a binary search; either gives the same entry.
class ProgramLaw {
 public:
  explicit ProgramLaw(const ControlProgram& program) : program_(program) {}
  Control operator()(double s_m, double) {
    const double x = s_m + 1e-9;
    const std::size_t n = program_.size();
    for (std::size_t k = cursor_; k < n && k <= cursor_ + 1; ++k) {
      if (!(x < program_[k].from_m) && (k + 1 == n || x < program_[k + 1].from_m)) {
        cursor_ = k;
        return program_[k].control;
      }
    }
    auto it = std::upper_bound(program_.begin(), program_.end(), x,
                               [](double s, const ProgramStep& p) { return s < p.from_m; });
    if (it != program_.begin()) cursor_ = static_cast<std::size_t>(it - program_.begin()) - 1;
    return it == program_.begin() ? program_.front().control : (it - 1)->control;
  }

 private:
  const ControlProgram& program_;
  std::size_t cursor_ = 0;
};

// Where steps must end: the breakpoints and the route's change points, ascending.
std::vector<double> events_of(const Route& route, std::vector<double> events) {
  for (double p : route.change_points_m()) events.push_back(p);
  std::sort(events.begin(), events.end());
  return events;
}

std::vector<double> program_breakpoints(const ControlProgram& program) {
  std::vector<double> breakpoints;
  breakpoints.reserve(program.size());
  for (const auto& step : program) breakpoints.push_back(step.from_m);
  return breakpoints;
}

// Where a run starts (or resumes): its state at the start of a step.
struct RunStart {
  double s = 0.0;
  double e = 0.0;
  double t = 0.0;
  std::size_t step = 0;  // steps taken before (numbers the checkpoints)
};

// The simulation loop, from `from` on, appending to `out` (which holds what came before). The
// law is a template parameter so that a program's look-up is inlined; checkpoints are kept
// every kCheckpointSteps steps when asked (no speed cap).
template <class Law>
void run(const Motion& motion, Law& law, const std::vector<double>& events,
         const SimulationOptions& opt, const RunStart& from, bool keep_checkpoints,
         SimulationResult& out) {
  const Route& route = motion.route();
  const Train& train = motion.train();
  const SpeedEnvelope& envelope = motion.envelope();
  const bool measured = train.has_efficiency_maps();
  const double length = route.length_m();
  double s = from.s;
  double e = from.e;
  double t = from.t;
  std::size_t step = from.step;
  std::size_t segment = route.index_at(s);
  auto next_event = std::upper_bound(events.begin(), events.end(), s + 1e-9);

  while (s < length - 1e-9) {
    if (keep_checkpoints && step % kCheckpointSteps == 0) {
      out.checkpoints.push_back({out.trace.size(), s, e, t, out.energy, out.max_overspeed_ms});
    }
    ++step;
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
      // The segment holding s, by a cursor (steps never cross a route change): the one
      // motion.substep would look up.
      segment = route.index_at(s, segment);
      sub = motion.substep_on(route.segments()[segment], s, e, next - s, c, opt.rk_order);
    }
    if (measured) {
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
    out.max_overspeed_ms = std::max(out.max_overspeed_ms, v1 - envelope.static_limit_ms(s));
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
    // Millimetre Euler steps over the first metre (a run that ends nearly at rest, where the
    // stop error decides whether it arrives), then steps of kCoarseBrakeStep_m: a run that
    // ends moving at speed has hundreds of metres of braking to extrapolate, and only its
    // being past the end counts.
    constexpr double kFineBrakeReach_m = 1.0, kCoarseBrakeStep_m = 0.1;
    while (ee > 0.0 && extra < 1e4) {
      const double h = extra < kFineBrakeReach_m ? 1e-3 : kCoarseBrakeStep_m;
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
}

SimulationResult start_result(const Route& route, const SimulationOptions& opt,
                              std::size_t event_count) {
  SimulationResult out;
  const double s = opt.start_position_m;
  out.trace.reserve(static_cast<std::size_t>((route.length_m() - s) / opt.step_m) + event_count +
                    2);
  return out;
}

RunStart start_of(const SimulationOptions& opt) {
  RunStart from;
  from.s = opt.start_position_m;
  from.e = 0.5 * opt.start_speed_ms * opt.start_speed_ms;
  return from;
}

}  // namespace

SimulationResult simulate(const Motion& motion, const ControlLaw& law,
                          const std::vector<double>& breakpoints_m, const SimulationOptions& opt) {
  const std::vector<double> events = events_of(motion.route(), breakpoints_m);
  SimulationResult out = start_result(motion.route(), opt, events.size());
  out.trace.push_back({0.0, opt.start_position_m, opt.start_speed_ms, 0.0, 0.0, Regime::Coast});
  auto call = [&law](double s_m, double v_ms) { return law(s_m, v_ms); };
  run(motion, call, events, opt, start_of(opt), false, out);
  return out;
}

namespace {
// What a later run must share with this one to resume from its checkpoints.
void mark_resumable(const Motion& motion, const ControlProgram& program,
                    const SimulationOptions& opt, SimulationResult& out) {
  out.checkpoint_program = program;
  out.checkpoint_motion = &motion;
  out.checkpoint_step_m = opt.step_m;
  out.checkpoint_rk_order = opt.rk_order;
  out.checkpoint_start_speed_ms = opt.start_speed_ms;
  out.checkpoint_start_position_m = opt.start_position_m;
}
}  // namespace

SimulationResult simulate(const Motion& motion, const ControlProgram& program,
                          const SimulationOptions& opt) {
  const std::vector<double> events = events_of(motion.route(), program_breakpoints(program));
  SimulationResult out = start_result(motion.route(), opt, events.size());
  out.trace.push_back({0.0, opt.start_position_m, opt.start_speed_ms, 0.0, 0.0, Regime::Coast});
  const bool resumable = !opt.speed_cap;
  if (resumable) mark_resumable(motion, program, opt, out);
  ProgramLaw law(program);
  run(motion, law, events, opt, start_of(opt), resumable, out);
  return out;
}

double first_difference_m(const ControlProgram& a, const ControlProgram& b) {
  const std::size_t n = std::min(a.size(), b.size());
  std::size_t i = 0;
  while (i < n && a[i].from_m == b[i].from_m && a[i].control == b[i].control) ++i;
  if (i == a.size() && i == b.size()) return std::numeric_limits<double>::infinity();
  // Before the first entry the first entry's control applies: a change there changes all.
  if (i == 0) return -std::numeric_limits<double>::infinity();
  double x = std::numeric_limits<double>::infinity();
  if (i < a.size()) x = std::min(x, a[i].from_m);
  if (i < b.size()) x = std::min(x, b[i].from_m);
  return x;
}

SimulationResult simulate(const Motion& motion, const ControlProgram& program,
                          const SimulationOptions& opt, const SimulationResult& earlier) {
  const bool same_options =
      !opt.speed_cap && !earlier.checkpoints.empty() && earlier.checkpoint_motion == &motion &&
      earlier.checkpoint_step_m == opt.step_m && earlier.checkpoint_rk_order == opt.rk_order &&
      earlier.checkpoint_start_speed_ms == opt.start_speed_ms &&
      earlier.checkpoint_start_position_m == opt.start_position_m;
  if (!same_options) return simulate(motion, program, opt);
  // The last checkpoint strictly before the first difference: every step before it ended
  // there or earlier, so strictly before the difference too.
  const double x = first_difference_m(program, earlier.checkpoint_program);
  std::size_t j = earlier.checkpoints.size();
  while (j > 0 && !(earlier.checkpoints[j - 1].s_m < x)) --j;
  if (j <= 1) return simulate(motion, program, opt);  // only the start: nothing to reuse
  const SimulationCheckpoint& cp = earlier.checkpoints[j - 1];

  const std::vector<double> events = events_of(motion.route(), program_breakpoints(program));
  SimulationResult out = start_result(motion.route(), opt, events.size());
  out.trace.insert(out.trace.end(), earlier.trace.begin(),
                   earlier.trace.begin() + static_cast<std::ptrdiff_t>(cp.trace_size));
  out.energy = cp.energy;
  out.max_overspeed_ms = cp.max_overspeed_ms;
  mark_resumable(motion, program, opt, out);
  out.checkpoints.assign(earlier.checkpoints.begin(),
                         earlier.checkpoints.begin() + static_cast<std::ptrdiff_t>(j - 1));
  RunStart from;
  from.s = cp.s_m;
  from.e = cp.e;
  from.t = cp.t_s;
  from.step = (j - 1) * kCheckpointSteps;
  ProgramLaw law(program);
  run(motion, law, events, opt, from, true, out);
  return out;
}

SimulationResult resume_prefix(const SimulationResult& run, double up_to_m) {
  SimulationResult out;
  std::size_t j = 0;
  while (j < run.checkpoints.size() && run.checkpoints[j].s_m < up_to_m) ++j;
  if (j == 0) return out;
  out.checkpoints.assign(run.checkpoints.begin(),
                         run.checkpoints.begin() + static_cast<std::ptrdiff_t>(j));
  out.trace.assign(run.trace.begin(), run.trace.begin() + static_cast<std::ptrdiff_t>(
                                                              out.checkpoints.back().trace_size));
  out.checkpoint_program = run.checkpoint_program;
  out.checkpoint_motion = run.checkpoint_motion;
  out.checkpoint_step_m = run.checkpoint_step_m;
  out.checkpoint_rk_order = run.checkpoint_rk_order;
  out.checkpoint_start_speed_ms = run.checkpoint_start_speed_ms;
  out.checkpoint_start_position_m = run.checkpoint_start_position_m;
  return out;
}

}  // namespace ecorail::physics
