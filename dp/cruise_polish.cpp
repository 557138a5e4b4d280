#include "dp/cruise_polish.hpp"

#include "dp/golden_section.hpp"
#include "dp/lambda_bracket.hpp"
#include "dp/nelder_mead.hpp"

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
  if (!(std::isfinite(price_search_step_m) && price_search_step_m > 0.0 &&
        price_search_step_m <= 50.0)) {
    return fail("cruise polish price_search_step_m must be in (0, 50] m");
  }
  if (!(std::isfinite(price_first_step_m) && price_first_step_m > 0.0)) {
    return fail("cruise polish price_first_step_m must be finite and > 0");
  }
  if (price_max_simulations < 1) return fail("cruise polish price_max_simulations must be >= 1");
  if (!(std::isfinite(price_time_tolerance_s) && price_time_tolerance_s > 0.0)) {
    return fail("cruise polish price_time_tolerance_s must be finite and > 0");
  }
  return true;
}

namespace {

using physics::Control;
using physics::ControlProgram;

constexpr double kInf = std::numeric_limits<double>::infinity();
// The hold-speed solve: at most this many re-simulations per coasting point.
constexpr int kMaxTimeSolves = 30;
// The price search: its first step in log lambda, and at most this many prices.
constexpr double kPriceBracketStep = 0.05;
constexpr int kMaxPrices = 12;
// Restarts of the simplex at one price, and the least gain (J) of one that earns another.
constexpr int kMaxRestarts = 4;
constexpr double kRestartGain_J = 1.0;
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
  auto end_of = [&](std::size_t k) { return k + 1 < n ? program[k + 1].from_m : length_m; };
  // The cruise starts at the first hold that is not short: the short holds and traction blips
  // before it (the grid's staircase up to the cruise speed) are traction.
  while (first < n && (program[first].control != Control::Hold ||
                       end_of(first) - program[first].from_m < options.short_phase_m)) {
    ++first;
  }
  if (first == n || first == 0 || first > last) return std::nullopt;
  if (last + 1 >= n) return std::nullopt;  // a cruise into the stop: nothing leaves it
  const double cruise_m = program[last + 1].from_m - program[first].from_m;
  if (cruise_m < options.min_cruise_m) return std::nullopt;
  CruiseShape shape;
  for (std::size_t k = 0; k < first; ++k) {
    const bool short_phase = k > 0 && end_of(k) - program[k].from_m < options.short_phase_m;
    if (short_phase) {
      ++shape.dropped;
      continue;
    }
    if (!shape.program.empty() && shape.program.back().control == program[k].control) continue;
    shape.program.push_back(program[k]);
  }
  if (shape.program.back().control != Control::MaxTraction) return std::nullopt;
  shape.program.push_back(program[first]);
  shape.hold = shape.program.size() - 1;
  auto is_short = [&](std::size_t k) {
    return k <= last && end_of(k) - program[k].from_m < options.short_phase_m;
  };
  for (std::size_t k = first + 1; k < n; ++k) {
    if (!is_short(k)) {
      if (shape.program.back().control != program[k].control) shape.program.push_back(program[k]);
      continue;
    }
    // A run of short phases (a staircase: short coasts and holds descending into a lower
    // limit, or blips of traction inside a cruise) becomes one phase of the control it spends
    // the most distance in; a run of one is dropped and the phase before it goes on.
    std::size_t j = k;
    double length_by_control[physics::kControlCount] = {};
    while (j < n && is_short(j)) {
      length_by_control[static_cast<int>(program[j].control)] += end_of(j) - program[j].from_m;
      ++j;
    }
    shape.dropped += static_cast<int>(j - k);
    if (j - k >= 2) {
      int dominant = 0;
      for (int c = 1; c < physics::kControlCount; ++c) {
        if (length_by_control[c] > length_by_control[dominant]) dominant = c;
      }
      const Control control = static_cast<Control>(dominant);
      if (shape.program.back().control != control) {
        shape.program.push_back({program[k].from_m, control});
        --shape.dropped;
      }
    }
    k = j - 1;
  }
  shape.exit = shape.program.size();
  for (std::size_t k = shape.program.size(); k-- > shape.hold;) {
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
           double tolerance_s, const PolishEnd& end, CruisePolishReport& report)
      : engine_(engine),
        start_(start),
        target_s_(target_s),
        tolerance_s_(tolerance_s),
        end_(end),
        report_(report) {}

  // Whether a run ends as asked.
  bool ends(const physics::SimulationResult& sim) const {
    return end_.moving ? end_.reaches(sim) : run_arrives(sim);
  }

  // The run of program at step_m, resumed from `earlier` (a run at that step, or empty). For a
  // run that ends at a pinned speed, the final brake's onset is solved first (the end speed
  // rises as braking starts later): only the tail after the onset is integrated again.
  physics::SimulationResult simulate(ControlProgram& program, double step_m,
                                     const physics::SimulationResult& earlier) {
    physics::SimulationResult sim = engine_.resimulate(program, start_, step_m, earlier);
    ++report_.simulations;
    if (!end_.moving || !std::isfinite(end_.pinned_speed_ms) ||
        program.back().control != Control::MaxBrake || program.size() < 2) {
      return sim;
    }
    const double target = end_.pinned_speed_ms;
    auto miss = [&](const physics::SimulationResult& r) {
      return end_.reaches(r) || r.end_speed_ms > target ? target - r.end_speed_ms : target;
    };
    if (std::abs(miss(sim)) <= 0.5 * end_.speed_tolerance_ms) return sim;
    const std::size_t k = program.size() - 1;
    const double lo = program[k - 1].from_m + 1e-6, hi = engine_.route().length_m() - 1e-6;
    if (!(lo < hi)) return sim;
    physics::SimulationResult trial;
    bool met = false;
    auto f = [&](double x) {
      program[k].from_m = x;
      trial = engine_.resimulate(program, start_, step_m, sim);
      ++report_.simulations;
      const double m = miss(trial);
      met = std::abs(m) <= 0.5 * end_.speed_tolerance_ms;
      return m;
    };
    const double f_lo = f(lo);
    if (met) return trial;
    const double f_hi = f(hi);
    if (met) return trial;
    if (!(f_lo >= 0.0 && f_hi <= 0.0)) return sim;
    LambdaBracket root(f, lo, f_lo, hi, f_hi, kMaxTimeSolves);
    root.narrow([&] { return met; }, kMinBracket_m);
    return trial;
  }

  // The run of program (hold speed free, everything else fixed) that meets the time at step_m:
  // the end of the traction phase before the hold is solved by a safeguarded secant on the
  // re-simulated time (which falls as the hold starts later, at a higher speed).
  Candidate meet_time(ControlProgram program, std::size_t hold, double step_m) {
    const double lo_limit = program[hold - 1].from_m + 1e-6;
    const double hi_limit = program[hold + 1].from_m - 1e-6;
    auto f_at = [&](double x, Candidate* out) {
      program[hold].from_m = x;
      Candidate c;
      // Consecutive runs differ from the hold's start on (the earlier of the two starts), so
      // each resumes, bit for bit, from the run before it.
      c.sim = simulate(program, step_m, recent_);
      c.program = program;
      recent_ = c.sim;
      // A run that does not arrive counts as too slow: the hold must start later.
      const double f = ends(c.sim) ? c.sim.running_time_s - target_s_ : kInf;
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
  const PolishEnd& end_;
  CruisePolishReport& report_;
  physics::SimulationResult recent_;  // the last run (empty: none yet)
};

}  // namespace

CruisePolishReport polish_cruise(const SectionEngine& engine, double target_s, double tolerance_s,
                                 const CruisePolishOptions& options, LambdaRun& run,
                                 const PolishEnd& end) {
  CruisePolishReport report;
  report.cost_before_J = run.cost_J;
  report.cost_after_J = run.cost_J;
  if (!options.enabled || !engine.options().cruise_as_hold ||
      !(end.moving ? end.reaches && end.reaches(run.sim) : run_arrives(run.sim)) ||
      std::abs(run.sim.running_time_s - target_s) > tolerance_s) {
    return report;
  }
  const double length_m = engine.route().length_m();
  std::optional<CruiseShape> shape = cruise_shape(run.program, length_m, options);
  if (!shape) return report;
  report.dropped_phases = shape->dropped;
  Polisher polisher(engine, run.start, target_s, tolerance_s, end, report);
  const std::size_t hold = shape->hold;
  // Every switch point from the first hold on is searched (each hold's start sets its speed,
  // each coast's start where it leaves), the final brake excepted: the stop's braking curve
  // starts it, or the end speed when the run ends at a pinned speed.
  std::vector<std::size_t> free;
  for (std::size_t k = hold; k < shape->program.size(); ++k) {
    if (k + 1 == shape->program.size() && shape->program[k].control == Control::MaxBrake &&
        (!end.moving || std::isfinite(end.pinned_speed_ms))) {
      break;
    }
    free.push_back(k);
  }
  const double floor_m = shape->program[hold - 1].from_m;
  auto program_at = [&](const std::vector<double>& x, ControlProgram* p) {
    *p = shape->program;
    double previous = floor_m;
    for (std::size_t i = 0; i < free.size(); ++i) {
      if (!(x[i] > previous + 1.0 && x[i] < length_m - 1.0)) return false;
      (*p)[free[i]].from_m = previous = x[i];
    }
    return free.back() + 1 >= p->size() || previous < (*p)[free.back() + 1].from_m - 1.0;
  };
  // One time price for the whole run: the switch points that minimise cost + lambda * time.
  // At that minimum every hold's speed and every coasting point meet the same Lagrange
  // condition (the marginal energy of a second saved is lambda everywhere), which a search of
  // one switch point with another solving the time cannot reach when a coast runs into a lower
  // limit (the cost has a kink there, and the optimum lies along it).
  const double price_step_m = std::max(options.search_step_m, options.price_search_step_m);
  physics::SimulationResult recent;
  auto lagrangian = [&](double lambda, const std::vector<double>& x, double* time_s) {
    ControlProgram p;
    if (!program_at(x, &p)) return kInf;
    recent = polisher.simulate(p, price_step_m, recent);
    if (!polisher.ends(recent)) return kInf;
    if (time_s != nullptr) *time_s = recent.running_time_s;
    return engine.energy_cost_J(recent) + lambda * recent.running_time_s;
  };
  std::vector<double> x(free.size());
  for (std::size_t i = 0; i < free.size(); ++i) x[i] = shape->program[free[i]].from_m;
  double first_step_m = options.price_first_step_m;
  auto time_at_price = [&](double log_lambda) {
    const double lambda = std::exp(log_lambda);
    // Restarted from its best vertex with a fresh simplex while that still gains: a simplex
    // that collapsed along the kink of a coast into a lower limit stops short of the optimum.
    auto lagrangian_at = [&](const std::vector<double>& y) {
      return lagrangian(lambda, y, nullptr);
    };
    NelderMeadResult m = nelder_mead_minimum(
        lagrangian_at, x, first_step_m, options.search_tolerance_m, options.price_max_simulations);
    for (int restart = 0; restart < kMaxRestarts && std::isfinite(m.f); ++restart) {
      const NelderMeadResult again =
          nelder_mead_minimum(lagrangian_at, m.x, options.price_first_step_m,
                              options.search_tolerance_m, options.price_max_simulations);
      const bool gained = again.f < m.f - kRestartGain_J;
      if (again.f < m.f) m = again;
      if (!gained) break;
    }
    if (!std::isfinite(m.f)) return kInf;
    x = m.x;
    first_step_m = std::max(options.search_tolerance_m, 0.25 * options.price_first_step_m);
    double time_s = kInf;
    lagrangian(lambda, x, &time_s);
    return time_s - target_s;
  };
  // The price whose optimum meets the time, to within price_time_tolerance_s; the last
  // hundredths are then met by the first hold's speed alone (meet_time).
  const double log_lambda0 = std::log(run.lambda > 0.0 ? run.lambda : 1.0);
  const double error0_s = time_at_price(log_lambda0);
  double error_s = error0_s;
  if (!(std::abs(error0_s) <= options.price_time_tolerance_s)) {
    // The bracket starts at the price already searched (its optimum is not searched again).
    LambdaBracket price(
        [&](double log_lambda) {
          return error_s = log_lambda == log_lambda0 ? error0_s : time_at_price(log_lambda);
        },
        log_lambda0, kPriceBracketStep, kMaxPrices);
    price.narrow([&] { return std::abs(error_s) <= options.price_time_tolerance_s; });
  }
  ControlProgram current;
  if (!program_at(x, &current)) return report;
  const double c0 = shape->program[shape->exit].from_m;
  const double c_best = current[shape->exit].from_m;
  double best_cost = kInf;
  {
    Candidate c = polisher.meet_time(current, hold, options.search_step_m);
    if (!c.program.empty()) {
      current = c.program;
      best_cost = c.cost_J;
    }
  }
  if (!std::isfinite(best_cost)) return report;
  // The result: the best coasting point at the engine's fine step, the time met there.
  Candidate fine = polisher.meet_time(current, hold, engine.options().resim_step_m);
  if (fine.program.empty() || !polisher.ends(fine.sim) ||
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
