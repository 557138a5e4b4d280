#include "dp/policy_extraction.hpp"

#include <cmath>

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
    const double energy =
        energy_cost_J(objective, motion.train(), adv.traction_work_J, adv.brake_work_J);
    return energy + value.lambda * adv.time_s +
           value.at(grid, next, physics::speed_from_e(adv.e_end));
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
