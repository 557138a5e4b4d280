#include "dp/cruise_polish.hpp"

#include "dp/golden_section.hpp"
#include "dp/lambda_bracket.hpp"

#include <cmath>
#include <limits>
#include <optional>
#include <utility>
#include <vector>

#include "dp/time_target.hpp"

namespace ecorail::dp {

bool CruisePolishOptions::IsValid(std::string* error) const {
  auto fail = [&](const char* what) {
    if (error != nullptr) *error = what;
    return false;
  };
  if (!(std::isfinite(min_cruise_m) && min_cruise_m >= 0.0)) {
    return fail("cruise polish min_cruise_m must be finite and >= 0");
  }
  if (!(std::isfinite(short_phase_m) && short_phase_m >= 0.0)) {
    return fail("cruise polish short_phase_m must be finite and >= 0");
  }
  if (!(std::isfinite(search_half_width_m) && search_half_width_m > 0.0)) {
    return fail("cruise polish search_half_width_m must be finite and > 0");
  }
  if (!(std::isfinite(search_tolerance_m) && search_tolerance_m > 0.0)) {
    return fail("cruise polish search_tolerance_m must be finite and > 0");
  }
  if (!(std::isfinite(search_step_m) && search_step_m > 0.0 && search_step_m <= 10.0)) {
    return fail("cruise polish search_step_m must be in (0, 10] m");
  }
  return true;
}

namespace {

using physics::Control;
using physics::ControlProgram;

constexpr double kInf = std::numeric_limits<double>::infinity();
// The hold-speed solve: at most this many re-simulations per coasting point.
constexpr int kMaxTimeSolves = 30;
// The narrowest bracket of a hold start worth another re-simulation.
constexpr double kMinBracket_m = 1e-9;

// The polished shape: one traction phase ending at the hold (index hold), the cruise, and the
// phase that leaves it (index exit).
struct CruiseShape {
  ControlProgram program;
  std::size_t hold = 0, exit = 0;
  int dropped = 0;
};

// Drops the short phases inside the cruise (first hold to last hold). nullopt when the program
// has no cruise to polish.
std::optional<CruiseShape> cruise_shape(const ControlProgram& program, double length_m,
                                        const CruisePolishOptions& options) {
  const std::size_t n = program.size();
  std::size_t first = n, last = n;
  for (std::size_t k = 0; k < n; ++k) {
    if (program[k].control != Control::Hold) continue;
    if (first == n) first = k;
    last = k;
  }
  if (first == n || first == 0 || program[first - 1].control != Control::MaxTraction) {
    return std::nullopt;
  }
  if (last + 1 >= n) return std::nullopt;  // a cruise into the stop: nothing leaves it
  const double cruise_m = program[last + 1].from_m - program[first].from_m;
  if (cruise_m < options.min_cruise_m) return std::nullopt;
  CruiseShape shape;
  for (std::size_t k = 0; k <= first; ++k) shape.program.push_back(program[k]);
  for (std::size_t k = first + 1; k < n; ++k) {
    const double to = k + 1 < n ? program[k + 1].from_m : length_m;
    if (k <= last && to - program[k].from_m < options.short_phase_m) {
      ++shape.dropped;  // the phase before it goes on
      continue;
    }
    if (shape.program.back().control == program[k].control) continue;
    shape.program.push_back(program[k]);
  }
  shape.hold = first;
  shape.exit = shape.program.size();
  for (std::size_t k = shape.program.size(); k-- > first;) {
    if (shape.program[k].control == Control::Hold) {
      shape.exit = k + 1;
      break;
    }
  }
  if (shape.exit >= shape.program.size()) return std::nullopt;
  return shape;
}

struct Candidate {
  ControlProgram program;
  physics::SimulationResult sim;
  double cost_J = kInf;
};

class Polisher {
 public:
  Polisher(const SectionEngine& engine, const StartState& start, double target_s,
           double tolerance_s, CruisePolishReport& report)
      : engine_(engine),
        start_(start),
        target_s_(target_s),
        tolerance_s_(tolerance_s),
        report_(report) {}

  // The run of program (hold speed free, everything else fixed) that meets the time at step_m:
  // the end of the traction phase before the hold is solved by a safeguarded secant on the
  // re-simulated time (which falls as the hold starts later, at a higher speed).
  Candidate meet_time(ControlProgram program, std::size_t hold, double step_m) {
    const double lo_limit = program[hold - 1].from_m + 1e-6;
    const double hi_limit = program[hold + 1].from_m - 1e-6;
    auto f_at = [&](double x, Candidate* out) {
      program[hold].from_m = x;
      Candidate c;
      c.program = program;
      // Consecutive runs differ from the hold's start on (the earlier of the two starts), so
      // each resumes, bit for bit, from the run before it.
      c.sim = engine_.resimulate(program, start_, step_m, recent_);
      recent_ = c.sim;
      ++report_.simulations;
      // A run that does not arrive counts as too slow: the hold must start later.
      const double f = run_arrives(c.sim) ? c.sim.running_time_s - target_s_ : kInf;
      c.cost_J = engine_.energy_cost_J(c.sim);
      *out = std::move(c);
      return f;
    };
    Candidate best;
    double x0 = std::min(std::max(program[hold].from_m, lo_limit), hi_limit);
    double f0 = f_at(x0, &best);
    if (std::abs(f0) <= tolerance_s_) return best;
    // Bracket by doubling steps from x0 (f falls with x).
    double lo = lo_limit, hi = hi_limit, f_lo = kInf, f_hi = -kInf;
    double step = 8.0;
    Candidate trial;
    if (f0 > 0.0) {
      lo = x0, f_lo = f0;
      for (double x = x0 + step;; step *= 2.0, x = x0 + step) {
        x = std::min(x, hi_limit);
        const double f = f_at(x, &trial);
        if (std::abs(f) <= tolerance_s_) return trial;
        if (f < 0.0) {
          hi = x, f_hi = f;
          break;
        }
        lo = x, f_lo = f;
        if (x >= hi_limit) return {};
      }
    } else {
      hi = x0, f_hi = f0;
      for (double x = x0 - step;; step *= 2.0, x = x0 - step) {
        x = std::max(x, lo_limit);
        const double f = f_at(x, &trial);
        if (std::abs(f) <= tolerance_s_) return trial;
        if (f > 0.0) {
          lo = x, f_lo = f;
          break;
        }
        hi = x, f_hi = f;
        if (x <= lo_limit) return {};
      }
    }
    // Narrow [lo, hi] with the engine's one root search (LambdaBracket: Illinois regula falsi,
    // bisection while an end does not arrive) until the time is met.
    bool met = false;
    LambdaBracket root(
        [&](double x) {
          const double f = f_at(x, &trial);
          met = std::abs(f) <= tolerance_s_;
          return f;
        },
        lo, f_lo, hi, f_hi, kMaxTimeSolves);
    root.narrow([&] { return met; }, kMinBracket_m);
    if (met) return trial;
    return {};
  }

 private:
  const SectionEngine& engine_;
  StartState start_;
  double target_s_, tolerance_s_;
  CruisePolishReport& report_;
  physics::SimulationResult recent_;  // the last run (empty: none yet)
};

}  // namespace

CruisePolishReport polish_cruise(const SectionEngine& engine, double target_s, double tolerance_s,
                                 const CruisePolishOptions& options, LambdaRun& run) {
  CruisePolishReport report;
  report.cost_before_J = run.cost_J;
  report.cost_after_J = run.cost_J;
  if (!options.enabled || !engine.options().cruise_as_hold || !run_arrives(run.sim) ||
      std::abs(run.sim.running_time_s - target_s) > tolerance_s) {
    return report;
  }
  const double length_m = engine.route().length_m();
  std::optional<CruiseShape> shape = cruise_shape(run.program, length_m, options);
  if (!shape) return report;
  report.dropped_phases = shape->dropped;
  Polisher polisher(engine, run.start, target_s, tolerance_s, report);
  const std::size_t hold = shape->hold;
  // Every coast that leaves a hold (the last one, and any before a descent) is searched in
  // turn, the others held where they are.
  std::vector<std::size_t> exits;
  for (std::size_t k = hold + 1; k < shape->program.size(); ++k) {
    if (shape->program[k].control == Control::Coast &&
        shape->program[k - 1].control == Control::Hold) {
      exits.push_back(k);
    }
  }
  const double c0 = shape->program[shape->exit].from_m;
  // The hold speed found for the last coasting point is where the next solve starts.
  ControlProgram current = shape->program;
  double best_cost = kInf;
  for (const std::size_t exit : exits) {
    // The coasting point stays after its hold starts and before the phase after it.
    const double c_start = current[exit].from_m;
    const double c_min =
        std::max(c_start - options.search_half_width_m, current[exit - 1].from_m + 1.0);
    const double c_max =
        std::min(c_start + options.search_half_width_m,
                 (exit + 1 < current.size() ? current[exit + 1].from_m : length_m) - 1.0);
    if (!(c_min < c_max)) continue;
    auto cost_at = [&](double c) {
      ControlProgram p = current;
      p[exit].from_m = c;
      Candidate cand = polisher.meet_time(std::move(p), hold, options.search_step_m);
      if (cand.program.empty()) return kInf;
      current[hold].from_m = cand.program[hold].from_m;
      return cand.cost_J;
    };
    // Golden section on the coasting point (the energy along the time constraint is unimodal
    // around the optimum; an infeasible point scores +inf and moves the bracket away from it).
    const GoldenSectionResult g =
        golden_section_minimum(cost_at, c_min, c_max, options.search_tolerance_m,
                               std::numeric_limits<int>::max(), /*ties_go_left=*/true);
    if (!std::isfinite(g.f)) continue;
    current[exit].from_m = g.x;
    best_cost = g.f;
  }
  if (!std::isfinite(best_cost)) return report;
  const double c_best = current[shape->exit].from_m;
  // The result: the best coasting point at the engine's fine step, the time met there.
  Candidate fine = polisher.meet_time(current, hold, engine.options().resim_step_m);
  if (fine.program.empty() || !run_arrives(fine.sim) ||
      std::abs(fine.sim.running_time_s - target_s) > tolerance_s || !(fine.cost_J < run.cost_J)) {
    return report;
  }
  report.applied = true;
  report.cost_after_J = fine.cost_J;
  report.coast_shift_m = c_best - c0;
  run.program = std::move(fine.program);
  run.sim = std::move(fine.sim);
  run.cost_J = fine.cost_J;
  return report;
}

}  // namespace ecorail::dp
