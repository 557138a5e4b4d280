#include "dp/timing_switch_descent.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "dp/dense_solve.hpp"

namespace ecorail::dp::timing {

namespace {

using physics::ControlProgram;
using physics::SimulationResult;

// A switch's weight stops growing with its room here (as in the Newton step on windows).
constexpr double kMaxRoom_m = 50.0;
// Restoring Newton steps per trial.
constexpr int kRestoreSteps = 6;
// A trial must take off at least this fraction of the cost to count as cheaper (the
// simulator's own noise on a run's cost is far below it).
constexpr double kLeastGain = 1e-7;
// Switches keep at least this far apart and from the fixed part of the run (m).
constexpr double kLeastGap_m = 1e-3;

class Descent {
 public:
  Descent(const SectionEngine& engine, const StartState& start, const EndCheck& end,
          double target_s, double from_m, const SwitchDescentOptions& options,
          const std::vector<HeldPassing>& held)
      : held_(held),
        engine_(engine),
        start_(start),
        end_(end),
        target_s_(target_s),
        from_m_(from_m),
        length_m_(engine.route().length_m()),
        options_(options),
        pinned_speed_(end.moving && end.min_ms == end.max_ms),
        step_m_(engine.options().resim_step_m) {}

  SwitchDescentResult run(const LambdaRun& given) {
    SwitchDescentResult out;
    if (!options_.IsValid()) return out;
    // The run given, at the engine's fine step: its cost, when it meets the equations.
    step_m_ = engine_.options().resim_step_m;
    Point given_pt{given.program, given.sim, {}, 0.0};
    if (!evaluate(given_pt)) return out;
    const double given_cost = max_abs(given_pt.r) <= 1.0 ? given_pt.cost : kInf;
    // The search at a coarser step (steps end at the switches, so it moves a run's time by
    // milliseconds, which the finish at the fine step takes back).
    step_m_ = engine_.search_step_m(options_.search_step_m);
    Point cur{given.program, given.sim, {}, 0.0};
    if (!evaluate(cur)) return out;
    double move = options_.first_move_m, compass = options_.first_move_m;
    std::vector<double> g, jac;  // at cur
    bool fresh = false;
    // A start that misses the equations (a phase added to the run given) is first brought
    // onto them by Newton steps.
    if (max_abs(cur.r) > 1.0) {
      if (!differences(cur, g, jac)) return out;
      ++out.rounds;
      const std::vector<std::size_t> sw = switches(cur.program);
      if (!restore(cur, jac, weights(cur.program, sw), sw)) {
        out.simulations = simulations_;
        return out;
      }
    }
    // A trial: cur with its switches moved by step, back onto the equations; kept when cheaper.
    auto try_step = [&](const std::vector<std::size_t>& sw, const std::vector<double>& w,
                        const std::vector<double>& step) {
      Point trial = cur;
      for (std::size_t c = 0; c < sw.size(); ++c) trial.program[sw[c]].from_m += step[c];
      if (!ordered(trial.program) || !evaluate(trial) || !restore(trial, jac, w, sw) ||
          !(trial.cost < cur.cost - kLeastGain * std::abs(cur.cost))) {
        return false;
      }
      cur = std::move(trial);
      fresh = false;
      return true;
    };
    while (out.rounds < options_.max_rounds && simulations_ < options_.max_simulations) {
      if (!fresh) {
        if (!differences(cur, g, jac)) break;
        fresh = true;
        ++out.rounds;
      }
      const std::vector<std::size_t> sw = switches(cur.program);
      const std::vector<double> w = weights(cur.program, sw);
      // Along the projected gradient, the step's largest switch move `move` (doubled after a
      // success, halved after a failure) ...
      // (Unweighted: a short phase the run wants longer, such as a hold grown from nothing,
      // must be free to grow; the restoration, weighted, leaves it alone.)
      const std::vector<double> unit(sw.size(), 1.0);
      const std::vector<double> d =
          projected_descent(g, moving_rows(jac, sw.size(), unit, nullptr), unit);
      double largest = 0.0;
      for (double x : d) largest = std::max(largest, std::abs(x));
      if (largest > 0.0 && move >= options_.least_move_m) {
        std::vector<double> step(d.size());
        for (std::size_t c = 0; c < d.size(); ++c) step[c] = move / largest * d[c];
        if (try_step(sw, w, step)) {
          move = std::min(2.0 * move, 4.0 * options_.first_move_m);
        } else {
          move *= 0.5;
        }
        continue;
      }
      // ... and where it no longer gains (a kink of the cost: the end's braking envelope, a
      // limit), one switch at a time either way by `compass`, quartered while none gains.
      bool gained = false;
      for (std::size_t c = 0; c < sw.size() && !gained; ++c) {
        for (const double sign : {1.0, -1.0}) {
          std::vector<double> step(sw.size(), 0.0);
          step[c] = sign * compass;
          if ((gained = try_step(sw, w, step))) break;
        }
      }
      if (gained) {
        move = options_.first_move_m;
      } else if ((compass *= 0.25) < options_.least_move_m) {
        break;
      }
    }
    // The finish at the fine step: back onto the equations there.
    step_m_ = engine_.options().resim_step_m;
    Point fine{cur.program, given.sim, {}, 0.0};
    bool met = evaluate(fine);
    if (met && max_abs(fine.r) > 1.0) {
      const std::vector<std::size_t> sw = switches(fine.program);
      met = differences(fine, g, jac) && restore(fine, jac, weights(fine.program, sw), sw);
    }
    if (met && fine.cost < given_cost - kLeastGain * std::abs(fine.cost) && end_(fine.sim)) {
      LambdaRun run = given;
      run.lambda = NAN;
      run.program = std::move(fine.program);
      run.sim = std::move(fine.sim);
      run.cost_J = fine.cost;
      run.kept.reset();
      out.run = std::move(run);
    }
    out.simulations = simulations_;
    return out;
  }

 private:
  struct Point {
    ControlProgram program;
    SimulationResult sim;
    std::vector<double> r;  // the equations, scaled so that |r| <= 1 is met
    double cost = 0.0;
  };

  // The switches that move: after from_m (the run before it meets the part's passing points).
  std::vector<std::size_t> switches(const ControlProgram& p) const {
    std::vector<std::size_t> sw;
    for (std::size_t k = 1; k < p.size(); ++k) {
      if (p[k].from_m > from_m_ + kLeastGap_m) sw.push_back(k);
    }
    return sw;
  }

  double room(const ControlProgram& p, std::size_t k) const {
    const double next = k + 1 < p.size() ? p[k + 1].from_m : length_m_;
    return std::min(
        {p[k].from_m - std::max(p[k - 1].from_m, from_m_), next - p[k].from_m, kMaxRoom_m});
  }

  std::vector<double> weights(const ControlProgram& p, const std::vector<std::size_t>& sw) const {
    std::vector<double> w;
    for (std::size_t k : sw) w.push_back(std::pow(std::max(room(p, k), kLeastGap_m), 2));
    return w;
  }

  bool ordered(const ControlProgram& p) const {
    for (std::size_t k = 1; k < p.size(); ++k) {
      const double next = k + 1 < p.size() ? p[k + 1].from_m : length_m_;
      if (!(p[k].from_m > p[k - 1].from_m + kLeastGap_m && p[k].from_m < next - kLeastGap_m)) {
        return false;
      }
    }
    return true;
  }

  // Simulates pt.program (resumed from pt.sim, the run of a program that agrees with it up to
  // its first difference) and fills its equations and cost; false when it does not reach the
  // end.
  bool evaluate(Point& pt) {
    pt.sim = engine_.resimulate(pt.program, start_, step_m_, pt.sim);
    ++simulations_;
    if (!end_.reaches_end(pt.sim)) return false;
    pt.r.clear();
    pt.r.push_back((pt.sim.running_time_s - target_s_) / (0.5 * kZeroWidthTime_s));
    for (const HeldPassing& h : held_) {
      const Passing at = passing_at(pt.sim.trace, h.s_m);
      if (finite(h.time_s)) pt.r.push_back((at.t_s - h.time_s) / (0.5 * kZeroWidthTime_s));
      if (finite(h.speed_ms)) pt.r.push_back((at.v_ms - h.speed_ms) / (0.5 * kZeroWidthSpeed_ms));
    }
    if (pinned_speed_) {
      pt.r.push_back((pt.sim.end_speed_ms - end_.min_ms) / (0.5 * kZeroWidthSpeed_ms));
    } else if (!end_(pt.sim)) {
      return false;
    }
    pt.cost = engine_.energy_cost_J(pt.sim);
    for (double x : pt.r) {
      if (!std::isfinite(x)) return false;
    }
    return std::isfinite(pt.cost);
  }

  // Forward differences of the cost (g) and of the equations (jac, q x u, row-major) in every
  // switch after from_m.
  bool differences(const Point& at, std::vector<double>& g, std::vector<double>& jac) {
    const std::vector<std::size_t> sw = switches(at.program);
    const std::size_t q = at.r.size(), u = sw.size();
    if (u == 0) return false;
    g.assign(u, 0.0);
    jac.assign(q * u, 0.0);
    for (std::size_t c = 0; c < u; ++c) {
      const std::size_t k = sw[c];
      double h = std::min(options_.difference_m, 0.25 * room(at.program, k));
      const double next = k + 1 < at.program.size() ? at.program[k + 1].from_m : length_m_;
      if (at.program[k].from_m + h >= next - kLeastGap_m) h = -h;
      Point moved = at;
      moved.program[k].from_m += h;
      if (!evaluate(moved)) {
        // (A switch whose move one way ends the run wrongly, e.g. a brake for the stop moved
        // earlier, is differenced the other way; one that fails both ways stays where it is.)
        moved = at;
        moved.program[k].from_m -= h;
        h = -h;
        if (!ordered(moved.program) || !evaluate(moved)) continue;
      }
      g[c] = (moved.cost - at.cost) / h;
      for (std::size_t i = 0; i < q; ++i) jac[i * u + c] = (moved.r[i] - at.r[i]) / h;
    }
    return true;
  }

  // The rows of jac (q x u) that move: an end speed held by the braking envelope (the run
  // ends on it, at the window's speed, whatever a switch does) has a row of zeros and is kept
  // by the envelope, not by the step; r of the same rows.
  static std::vector<double> moving_rows(const std::vector<double>& jac, std::size_t u,
                                         const std::vector<double>& w, std::vector<double>* r) {
    const std::size_t q = jac.size() / std::max<std::size_t>(u, 1);
    std::vector<double> rows, kept_r;
    for (std::size_t i = 0; i < q; ++i) {
      double norm = 0.0;
      for (std::size_t c = 0; c < u; ++c) norm += jac[i * u + c] * jac[i * u + c] * w[c];
      if (!(norm > 1e-18)) continue;
      rows.insert(rows.end(), jac.begin() + i * u, jac.begin() + (i + 1) * u);
      if (r) kept_r.push_back((*r)[i]);
    }
    if (r) *r = kept_r;
    return rows;
  }

  // (J W J^T)^-1 b (J: q x u); false when singular.
  static bool solve_small(const std::vector<double>& jac, const std::vector<double>& w,
                          std::size_t q, std::vector<double>& b) {
    if (q == 0) return true;
    const std::size_t u = w.size();
    std::vector<double> a(q * q, 0.0);
    double largest = 0.0;
    for (std::size_t i = 0; i < q; ++i) {
      for (std::size_t j = 0; j < q; ++j) {
        for (std::size_t c = 0; c < u; ++c) a[i * q + j] += jac[i * u + c] * w[c] * jac[j * u + c];
      }
      largest = std::max(largest, std::abs(a[i * q + i]));
    }
    return largest > 0.0 && solve_dense(a, b, q, 1e-12 * largest);
  }

  // -W g projected onto the tangent of the equations: -W g + W J^T (J W J^T)^-1 J W g.
  static std::vector<double> projected_descent(const std::vector<double>& g,
                                               const std::vector<double>& jac,
                                               const std::vector<double>& w) {
    const std::size_t u = g.size(), q = jac.size() / std::max<std::size_t>(u, 1);
    std::vector<double> d(u, 0.0), y(q, 0.0);
    if (q == 0) {
      for (std::size_t c = 0; c < u; ++c) d[c] = -w[c] * g[c];
      return d;
    }
    for (std::size_t i = 0; i < q; ++i) {
      for (std::size_t c = 0; c < u; ++c) y[i] += jac[i * u + c] * w[c] * g[c];
    }
    if (!solve_small(jac, w, q, y)) return d;
    for (std::size_t c = 0; c < u; ++c) {
      double jty = 0.0;
      for (std::size_t i = 0; i < q; ++i) jty += jac[i * u + c] * y[i];
      d[c] = -w[c] * g[c] + w[c] * jty;
    }
    return d;
  }

  // Newton steps with the Jacobian of the point the trial left from, until both equations
  // hold within their half tolerance.
  bool restore(Point& pt, const std::vector<double>& jac, const std::vector<double>& w,
               const std::vector<std::size_t>& sw) {
    const std::size_t u = sw.size();
    const std::vector<double> rows = moving_rows(jac, u, w, nullptr);
    const std::size_t q = rows.size() / std::max<std::size_t>(u, 1);
    for (int it = 0; it < kRestoreSteps; ++it) {
      if (max_abs(pt.r) <= 1.0) return true;
      std::vector<double> y = pt.r;
      moving_rows(jac, u, w, &y);
      if (q == 0 || !solve_small(rows, w, q, y)) return false;
      for (std::size_t c = 0; c < u; ++c) {
        double jty = 0.0;
        for (std::size_t i = 0; i < q; ++i) jty += rows[i * u + c] * y[i];
        pt.program[sw[c]].from_m -= w[c] * jty;
      }
      if (!ordered(pt.program) || !evaluate(pt)) return false;
    }
    return max_abs(pt.r) <= 1.0;
  }

  std::vector<HeldPassing> held_;
  const SectionEngine& engine_;
  StartState start_;
  const EndCheck& end_;
  double target_s_ = 0.0, from_m_ = 0.0, length_m_ = 0.0;
  SwitchDescentOptions options_;
  bool pinned_speed_ = false;
  double step_m_ = 0.0;  // of the re-simulations: coarse while searching, then fine
  int simulations_ = 0;
};

}  // namespace

SwitchDescentResult descend_switches(const SectionEngine& engine, const StartState& start,
                                     const EndCheck& end, double target_s, const LambdaRun& run,
                                     double from_m, const SwitchDescentOptions& options,
                                     const std::vector<HeldPassing>& held) {
  return Descent(engine, start, end, target_s, from_m, options, held).run(run);
}

}  // namespace ecorail::dp::timing
