#include "dp/policy_extraction.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace ecorail::dp {

namespace {

using physics::Control;

struct Scorer {
  const physics::Motion& motion;
  const StageGrid& grid;
  const ValueFunction& value;
  Objective objective;
  const physics::StepSettings& step;
  double tie_tolerance;

  double q(double s, double e, Control c) const {
    const int next = grid.next_stage_after(s);
    const physics::Advance adv = motion.advance(s, e, grid.position(next), c, step);
    if (adv.stalled) return kInfeasible;
    if (!inside_transition_band(s, e, next, adv.e_end)) return kInfeasible;
    const double energy = energy_cost_J(objective, motion.train(), adv.traction_work_J,
                                        adv.brake_work_J, adv.traction_input_J, adv.regen_J);
    return energy + value.price(next - 1) * adv.time_s +
           value.at(grid, next, physics::speed_from_e(adv.e_end));
  }

  // Whether the advance from (s, e) to stage next (ending at e_end) keeps the band on the
  // transitions out of stage next - 1, as the sweep did (v^2 linear in the distance): a point
  // already passed, or no band, holds.
  bool inside_transition_band(double s, double e, int next, double e_end) const {
    const SpeedBand* band = value.transition_band(next - 1);
    if (band == nullptr) return true;
    const double s0 = grid.position(next - 1), s1 = grid.position(next);
    const double point_m = s0 + band->at_fraction * (s1 - s0);
    if (s >= point_m) return true;
    return band->passes(2.0 * e, 2.0 * e_end, (point_m - s) / (s1 - s));
  }

  // Best control at (s, e); the incumbent wins ties so the program does not chatter between
  // controls that do the same thing (e.g. all of them following the envelope).
  Control best(double s, double e, Control incumbent) const {
    double q_inc = q(s, e, incumbent);
    Control arg = incumbent;
    double q_best = q_inc;
    for (int c = 0; c < physics::kControlCount; ++c) {
      const auto control = static_cast<Control>(c);
      if (control == incumbent) continue;
      const double qc = q(s, e, control);
      if (qc < q_best) {
        q_best = qc;
        arg = control;
      }
    }
    const double tie = tie_tolerance * std::abs(q_best) + 1e-6;
    return q_inc <= q_best + tie ? incumbent : arg;
  }
};

}  // namespace

physics::ControlProgram extract_program(const physics::Motion& motion, const StageGrid& grid,
                                        const ValueFunction& value, Objective objective,
                                        const ExtractionSettings& settings) {
  const Scorer scorer{motion, grid, value, objective, settings.dp_step, settings.tie_tolerance};
  const physics::StepSettings fine{settings.decision_step_m, 4};
  const double length = motion.route().length_m();

  physics::ControlProgram program;
  double s = settings.start_position_m;
  double e = 0.5 * settings.start_speed_ms * settings.start_speed_ms;
  // From rest at the start, the sweep's own choice; mid-run, the look-ahead's.
  Control current = static_cast<Control>(value.best[grid.offset(0)]);
  if (s > 0.0 || e > 0.0) current = scorer.best(s, e, current);
  program.push_back({s, current});
  while (s < length - 1e-9) {
    const double next = std::min(length, s + settings.decision_step_m);
    const physics::Advance adv = motion.advance(s, e, next, current, fine);
    if (adv.stalled) break;
    const Control chosen = scorer.best(next, adv.e_end, current);
    if (chosen != current) {
      // Bisect the switch position on [s, next]: left of it the incumbent is still best.
      double lo = s, hi = next;
      Control right = chosen;
      for (int k = 0; k < settings.bisections; ++k) {
        const double mid = 0.5 * (lo + hi);
        const physics::Advance to_mid = motion.advance(s, e, mid, current, fine);
        const Control at_mid = to_mid.stalled ? chosen : scorer.best(mid, to_mid.e_end, current);
        if (at_mid == current) {
          lo = mid;
        } else {
          hi = mid;
          right = at_mid;
        }
      }
      const physics::Advance to_switch = motion.advance(s, e, hi, current, fine);
      s = hi;
      e = to_switch.e_end;
      current = right;
      program.push_back({s, current});
      continue;
    }
    s = next;
    e = adv.e_end;
  }
  return simplify_program(program, settings.min_entry_m);
}

namespace {

// Speed and time of a re-simulated run at position s (linear between trace points).
struct TraceState {
  double v_ms = 0.0, t_s = 0.0;
};
// The first trace point at or past s.
BigVector<physics::TracePoint>::const_iterator point_from(
    const BigVector<physics::TracePoint>& trace, double s) {
  return std::lower_bound(trace.begin(), trace.end(), s,
                          [](const physics::TracePoint& p, double x) { return p.s_m < x; });
}
TraceState state_at(const BigVector<physics::TracePoint>& trace, double s) {
  if (trace.empty()) return {};
  const auto it = point_from(trace, s);
  if (it == trace.begin()) return {it->v_ms, it->t_s};
  if (it == trace.end()) return {trace.back().v_ms, trace.back().t_s};
  const auto& b = *it;
  const auto& a = *(it - 1);
  const double w = b.s_m > a.s_m ? (s - a.s_m) / (b.s_m - a.s_m) : 1.0;
  return {a.v_ms + w * (b.v_ms - a.v_ms), a.t_s + w * (b.t_s - a.t_s)};
}

bool swings(Control c) {
  return c == Control::MaxTraction || c == Control::Coast;
}

// Whether every trace point strictly inside (from_m, to_m) has a speed between v_a and v_b
// (within 1 km/h).
bool stays_between(const BigVector<physics::TracePoint>& trace, double from_m, double to_m,
                   double v_a, double v_b) {
  constexpr double kSlack_ms = 1.0 / 3.6;
  const double lo = std::min(v_a, v_b) - kSlack_ms, hi = std::max(v_a, v_b) + kSlack_ms;
  auto it = std::upper_bound(trace.begin(), trace.end(), from_m,
                             [](double x, const physics::TracePoint& p) { return x < p.s_m; });
  for (; it != trace.end() && it->s_m < to_m; ++it) {
    if (it->v_ms < lo || it->v_ms > hi) return false;
  }
  return true;
}

// Whether the run reaches s riding a speed limit (traction the limit caps).
bool rides_limit_into(const BigVector<physics::TracePoint>& trace, double s) {
  const auto it = point_from(trace, s);
  if (it == trace.begin()) return false;
  return std::prev(it)->regime == physics::Regime::PartialTraction;
}

// Whether the switch speeds a..b of a saw tooth trend: its peaks fall (or rise) from each to
// the next, so do its troughs, and the peaks move further in all than the tooth swings on
// average. The grid makes such a staircase down a slow climb (a traction tenth of a km/h after
// each coast); a hold keeps one speed where the staircase keeps changing its own. On
// TTOBench St Gallen - Wil after 20 km (KISS, 2 m grid) a hold at 90 km/h over a staircase
// down to 86.6 km/h ran 1 s faster for 6 MJ more at the same time price.
bool trends(const physics::ControlProgram& program, const BigVector<physics::TracePoint>& trace,
            std::size_t a, std::size_t b) {
  std::vector<double> peaks, troughs;
  double swing = 0.0, last = NAN;
  for (std::size_t k = a; k <= b; ++k) {
    const double v = state_at(trace, program[k].from_m).v_ms;
    // A switch into a coast ends traction: a peak.
    (program[k].control == Control::Coast ? peaks : troughs).push_back(v);
    if (!std::isnan(last)) swing += std::abs(v - last);
    last = v;
  }
  if (peaks.size() < 3 || troughs.size() < 3) return false;
  swing /= static_cast<double>(b - a);
  auto monotone = [](const std::vector<double>& x, double sign) {
    for (std::size_t k = 1; k < x.size(); ++k) {
      if (!(sign * (x[k] - x[k - 1]) > 0.0)) return false;
    }
    return true;
  };
  for (const double sign : {-1.0, 1.0}) {
    if (monotone(peaks, sign) && monotone(troughs, sign) &&
        std::abs(peaks.back() - peaks.front()) > swing) {
      return true;
    }
  }
  return false;
}

}  // namespace

physics::ControlProgram hold_cruising(const physics::ControlProgram& program,
                                      const physics::SimulationResult& sim,
                                      const CruiseSettings& settings) {
  const auto& trace = sim.trace;
  const std::size_t n = program.size();
  if (n < 4 || trace.size() < 2) return program;
  physics::ControlProgram out;
  std::size_t i = 0;
  while (i < n) {
    // The longest run i..j of alternating traction and coasting whose switch speeds stay in
    // the band.
    std::size_t j = i;
    double v_lo = INFINITY, v_hi = -INFINITY;
    double v_start = state_at(trace, program[i].from_m).v_ms;  // at the start of phase j
    while (swings(program[i].control) && j + 1 < n && swings(program[j + 1].control) &&
           program[j + 1].control != program[j].control) {
      const double v = state_at(trace, program[j + 1].from_m).v_ms;
      const double lo = std::min(v_lo, v), hi = std::max(v_hi, v);
      const double band_kmh = (hi - lo) * 3.6;
      if (band_kmh > settings.max_band_kmh ||
          band_kmh > settings.max_band_fraction * 0.5 * (hi + lo) * 3.6) {
        break;
      }
      // A saw tooth swings: traction ends at a peak, the coast after it falls to a trough. A
      // coast that gains speed (down a descent) makes a staircase, which is no cruise: held at
      // its mean speed, a staircase from a limit down a dip and up to a cruise (TTOBench St
      // Gallen - Wil after 20 km, KISS) ran 26 s slower and met the time at a price that cost
      // 0.5 % more than the grid's own run.
      if (program[j].control == Control::MaxTraction ? v < v_start : v > v_start) break;
      // Each phase of the tooth runs between its end speeds. A long coast that dips through a
      // climb and comes back up a descent between two traction phases riding a limit ends
      // near where it began, but it is no tooth: held at the mean speed it is dearer than the
      // coast (a 14.6 km descent into a lower limit, VIRM6, 600 s: +2.1 %).
      if (j > i && !stays_between(trace, program[j].from_m, program[j + 1].from_m, v_start, v)) {
        break;
      }
      v_lo = lo, v_hi = hi, v_start = v;
      ++j;
    }
    // Switches i+1..j: j - i of them, alternating maxima and minima of the speed.
    if (static_cast<int>(j - i) >= settings.min_swings && trends(program, trace, i + 1, j)) {
      // A staircase, kept whole (its last few steps alone would pass for a saw tooth).
      out.insert(out.end(), program.begin() + static_cast<std::ptrdiff_t>(i),
                 program.begin() + static_cast<std::ptrdiff_t>(j) + 1);
      i = j + 1;
      continue;
    }
    if (static_cast<int>(j - i) < settings.min_swings) {
      out.push_back(program[i]);
      ++i;
      continue;
    }
    // The hold's speed: the mean over the saw tooth proper (from the first switch to the last).
    const double s_a = program[i + 1].from_m, s_b = program[j].from_m;
    const double dt = state_at(trace, s_b).t_s - state_at(trace, s_a).t_s;
    const double v_hold = dt > 0.0 ? (s_b - s_a) / dt : state_at(trace, s_a).v_ms;
    // Where the run's first phase reaches that speed (traction rising through it, or coasting
    // falling through it); at its end when it does not.
    double x = s_a;
    bool reached = false;
    const bool rising = program[i].control == Control::MaxTraction;
    for (std::size_t k = 1; k < trace.size(); ++k) {
      const auto& a = trace[k - 1];
      const auto& b = trace[k];
      if (b.s_m <= program[i].from_m) continue;
      if (a.s_m >= s_a) break;
      const bool crosses =
          rising ? (a.v_ms < v_hold && b.v_ms >= v_hold) : (a.v_ms > v_hold && b.v_ms <= v_hold);
      if (crosses) {
        const double w = (v_hold - a.v_ms) / (b.v_ms - a.v_ms);
        x = std::max(program[i].from_m, a.s_m + w * (b.s_m - a.s_m));
        reached = true;
        break;
      }
    }
    // A first phase that rides a limit above the tooth's mean speed never reaches it, and a
    // hold from its end would keep the limit's speed, not the tooth's (on the St Gallen - Wil
    // descent, 1 m grid, a hold at the 90 km/h limit over a tooth at 88 km/h ran 1.3 s faster
    // for 6 MJ more at the same time price). The ride is kept, and the tooth is looked for
    // again from its own first coast, which reaches the mean.
    if (!reached && state_at(trace, s_a).v_ms > v_hold && rides_limit_into(trace, s_a)) {
      out.push_back(program[i]);
      ++i;
      continue;
    }
    if (x > program[i].from_m) out.push_back(program[i]);
    out.push_back({x, Control::Hold});
    out.push_back(program[j]);
    i = j + 1;
  }
  return simplify_program(out, 0.0);
}

namespace {
// Index of the program entry in force at s.
std::size_t entry_at(const physics::ControlProgram& program, double s) {
  std::size_t k = 0;
  while (k + 1 < program.size() && program[k + 1].from_m <= s) ++k;
  return k;
}
// Braking below the limit: more than this under the envelope's speed counts as the hold's.
constexpr double kBelowLimit_ms = 0.2;
}  // namespace

physics::ControlProgram coast_instead_of_braking_holds(
    const physics::ControlProgram& program, physics::SimulationResult& sim,
    const physics::SpeedEnvelope& envelope,
    const std::function<physics::SimulationResult(const physics::ControlProgram&)>& simulate,
    int max_rounds) {
  physics::ControlProgram out = program;
  for (int round = 0; round < max_rounds; ++round) {
    // The first trace point where a hold brakes below the limit.
    const auto& trace = sim.trace;
    std::size_t hit = trace.size();
    for (std::size_t k = 1; k < trace.size(); ++k) {
      const physics::TracePoint& p = trace[k];
      if (p.regime != physics::Regime::PartialBrake) continue;
      if (out[entry_at(out, trace[k - 1].s_m)].control != Control::Hold) continue;
      const double limit = physics::speed_from_e(envelope.e_at(p.s_m));
      if (p.v_ms < limit - kBelowLimit_ms) {
        hit = k;
        break;
      }
    }
    if (hit == trace.size()) break;
    const double x_brake = trace[hit - 1].s_m, v_hold = trace[hit - 1].v_ms;
    const std::size_t k_hold = entry_at(out, x_brake);
    const double next_m =
        k_hold + 1 < out.size() ? out[k_hold + 1].from_m : std::numeric_limits<double>::infinity();
    // Coast from where the hold starts braking ...
    physics::ControlProgram trial = out;
    trial.insert(trial.begin() + static_cast<long>(k_hold) + 1, {x_brake, Control::Coast});
    if (trial[k_hold].from_m >= x_brake) trial.erase(trial.begin() + static_cast<long>(k_hold));
    physics::SimulationResult coasting = simulate(trial);
    // ... and hold again where the speed is back down to the hold's (if it is before the
    // next entry).
    double x_back = std::numeric_limits<double>::quiet_NaN();
    for (std::size_t k = 1; k < coasting.trace.size(); ++k) {
      const physics::TracePoint& p = coasting.trace[k];
      if (p.s_m <= x_brake + 1.0) continue;
      if (p.s_m >= next_m) break;
      if (p.v_ms <= v_hold) {
        x_back = p.s_m;
        break;
      }
    }
    if (!std::isnan(x_back)) {
      const std::size_t k_coast = entry_at(trial, x_brake);
      trial.insert(trial.begin() + static_cast<long>(k_coast) + 1, {x_back, Control::Hold});
      coasting = simulate(trial);
    }
    out = simplify_program(trial, 0.0);
    sim = std::move(coasting);
  }
  return out;
}

physics::ControlProgram merge_short_entries(const physics::ControlProgram& program,
                                            const physics::SimulationResult& sim,
                                            double min_length_m, double min_duration_s,
                                            int* merged) {
  const double end_m = sim.trace.empty() ? 0.0 : sim.trace.back().s_m;
  physics::ControlProgram out;
  int dropped = 0;
  for (std::size_t k = 0; k < program.size(); ++k) {
    const double from = program[k].from_m;
    const double to = k + 1 < program.size() ? program[k + 1].from_m : std::max(from, end_m);
    const double duration = state_at(sim.trace, to).t_s - state_at(sim.trace, from).t_s;
    const bool short_entry = (min_length_m > 0.0 && to - from < min_length_m) ||
                             (min_duration_s > 0.0 && duration < min_duration_s);
    if (k > 0 && short_entry) {
      ++dropped;  // the control before it runs on
      continue;
    }
    if (!out.empty() && out.back().control == program[k].control) continue;
    out.push_back(program[k]);
  }
  if (merged != nullptr) *merged = dropped;
  return out;
}

physics::ControlProgram simplify_program(const physics::ControlProgram& program,
                                         double min_entry_m) {
  physics::ControlProgram out;
  for (std::size_t k = 0; k < program.size(); ++k) {
    const bool last = k + 1 == program.size();
    const bool sliver = k > 0 && !last && program[k + 1].from_m - program[k].from_m < min_entry_m;
    if (sliver) continue;  // the control before it simply goes on
    if (!out.empty() && out.back().control == program[k].control) continue;
    out.push_back(program[k]);
  }
  return out;
}

}  // namespace ecorail::dp
