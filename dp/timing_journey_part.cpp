#include "dp/timing_journey_part.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include "dp/cruise_polish.hpp"
#include "dp/dense_solve.hpp"
#include "dp/lambda_bracket.hpp"
#include "dp/policy_extraction.hpp"
#include "dp/regimes.hpp"
#include "dp/text_format.hpp"
#include "dp/timing_family_run.hpp"
#include "dp/timing_label_search.hpp"
#include "dp/timing_switch_descent.hpp"
#include "physics/units.hpp"

namespace ecorail::dp::timing {

Passing passing_at(const BigVector<physics::TracePoint>& trace, double s) {
  if (trace.empty() || s > trace.back().s_m + 1e-6) return {};
  const auto it =
      std::lower_bound(trace.begin(), trace.end(), s,
                       [](const physics::TracePoint& p, double x) { return p.s_m < x; });
  if (it == trace.begin()) return {it->t_s, it->v_ms};
  if (it == trace.end()) return {trace.back().t_s, trace.back().v_ms};
  const auto& b = *it;
  const auto& a = *(it - 1);
  const double w = b.s_m > a.s_m ? (s - a.s_m) / (b.s_m - a.s_m) : 1.0;
  return {a.t_s + w * (b.t_s - a.t_s), a.v_ms + w * (b.v_ms - a.v_ms)};
}

std::string point_name(int i, const TimingWindow& w) {
  return format_text("timing point %d (%.1f m)", i + 1, w.position_m);
}

bool EndCheck::reaches_end(const physics::SimulationResult& sim) const {
  if (!moving) return run_arrives(sim);
  return !sim.stopped_early && !sim.trace.empty() &&
         sim.trace.back().s_m >= sim.end_position_m - sim.stop_error_m - physics::kArrivalSlack_m;
}

bool EndCheck::operator()(const physics::SimulationResult& sim) const {
  if (!moving) return run_arrives(sim);
  return reaches_end(sim) && sim.end_speed_ms >= min_ms - tol_ms &&
         sim.end_speed_ms <= max_ms + tol_ms;
}

namespace {

constexpr double kMaxTrim_s = 1.0;
// Parts longer than this are not polished by runs of a few phases (dp/timing_family_run.hpp):
// one hold over kilometres of a real line meets its limits and gradients, and each of the
// searches' hundreds of simulations costs more.
constexpr double kFamilyReach_m = 5000.0;
// A descent on a run's switches replaces it when it saves at least this fraction of its cost
// (a smaller saving is not worth losing the run's time prices for).
constexpr double kDescentGain = 1e-5;
// A phase added before a part's end for the descent to grow (m from the end).
constexpr double kEndPhase_m = 5.0;
// Re-simulations all the descents of one part may take (a short part's run takes a fraction
// of a millisecond, one of 5 km a few).
constexpr int kDescentSimulations = 3000;
// Parts ending at a stop are descended up to this long, with at most this many
// re-simulations (a run of 15 km at the descent's 2 m step takes about a millisecond).
constexpr double kStopDescentReach_m = 20000.0;
constexpr int kStopDescentSimulations = 1500;
// The label search's time buckets (s), tried in turn (dp/timing_label_search.hpp).
constexpr double kLabelTimeBuckets_s[] = {1.0, 0.5};
// RK4 step of a trim's search runs (trim_switch); the result is checked on a fine run.
constexpr double kCoarseTrimStep_m = 0.5;

// Prices closer than this (in log lambda) are not told apart: on a grid the running time is a
// step function of the price, and a bracket this narrow that still holds a sign change holds a
// jump of the time (seconds between neighbouring prices), which no narrower bracket resolves;
// the switch-point trims close what is left. (The width at which LambdaBracket stops by default,
// as the single-section search does.)
constexpr double kNarrowestLogPrice = 1e-4;

// Where f, falling in x = log(lambda), crosses 0 on [x_min, x_max]: steps from x0 (growing
// steps, so a far root is bracketed within the small budgets of the price searches) until the
// sign changes, then the engine's one root search narrows the bracket (dp::LambdaBracket,
// regula falsi, Illinois). A value within tol is the root and ends the search. f may return
// +infinity ("too slow"). The caller keeps the run it wants from its own evaluations.
template <typename F>
void falling_root(F f, double x0, double step, double x_min, double x_max, int budget, double tol) {
  int n = 0;
  bool found = false;
  auto g = [&](double x) {
    ++n;
    const double e = f(x);
    if (std::abs(e) <= tol) {
      found = true;
      return 0.0;
    }
    return e;
  };
  double xa = std::clamp(x0, x_min, x_max), fa = g(xa);
  if (found) return;
  double xb = xa, fb = fa;
  if (fa > 0.0) {
    while (fb > 0.0 && n < budget && xb < x_max) {
      xa = xb, fa = fb;
      xb = std::min(x_max, xb + step);
      fb = g(xb);
      if (found) return;
      step *= 1.5;
    }
    if (fb > 0.0) return;
  } else {
    while (fa < 0.0 && n < budget && xa > x_min) {
      xb = xa, fb = fa;
      xa = std::max(x_min, xa - step);
      fa = g(xa);
      if (found) return;
      step *= 1.5;
    }
    if (fa < 0.0) return;
  }
  LambdaBracket bracket(g, xa, fa, xb, fb, budget - n);
  bracket.narrow([&] { return found; }, kNarrowestLogPrice);
}

// Moves one switch point of run's program with lo_m < position < hi_m (the end of a traction
// phase, or the onset of braking: later is faster for both) so that error(sim) (a time minus
// its target, falling as the switch moves later) is within tol_s; the first candidate that
// brackets the root is bisected. Switches outside (lo_m, hi_m) do not move, so a trim after a
// timing point leaves its passing time alone. A candidate must reach the end as `arrives` asks.
// Returns the evaluations used.
template <typename Error>
int trim_switch_at(const SectionEngine& engine, const EndCheck& arrives, LambdaRun& run,
                   double lo_m, double hi_m, Error error, double tol_s, double max_trim_s,
                   double step_m) {
  int used = 0;
  // Only a last correction: a larger miss is the price search's to close, not a switch's.
  const double miss = std::abs(error(run.sim));
  if (miss <= tol_s || !(miss <= max_trim_s)) return used;
  const physics::ControlProgram program = run.program;
  const double length = engine.route().length_m();

  for (std::size_t k = 1; k < program.size(); ++k) {
    const bool traction_end = program[k - 1].control == physics::Control::MaxTraction;
    const bool brake_onset = program[k].control == physics::Control::MaxBrake;
    if (!(traction_end || brake_onset)) continue;
    if (!(program[k].from_m > lo_m && program[k].from_m < hi_m)) continue;
    double a = std::max(program[k - 1].from_m, lo_m) + 1e-6;
    double b = std::min(k + 1 < program.size() ? program[k + 1].from_m : length, hi_m) - 1e-6;
    if (!(b > a)) continue;
    auto at = [&](double x, physics::ControlProgram* p_out, physics::SimulationResult* s_out) {
      physics::ControlProgram p = program;
      p[k].from_m = x;
      // (Resumed from the run's own re-simulation where the programs agree: bit for bit a
      // full run, without re-integrating the steps before the switch.)
      physics::SimulationResult sim = engine.resimulate(p, run.start, step_m, run.sim);
      ++used;
      const double e = arrives(sim) ? error(sim) : kInf;
      if (p_out) *p_out = std::move(p);
      if (s_out) *s_out = std::move(sim);
      return e;
    };
    double fa = at(a, nullptr, nullptr), fb = at(b, nullptr, nullptr);
    if (!(fa >= 0.0 && fb <= 0.0) || !finite(fb)) continue;
    // The time is smooth in the switch's position: the engine's one root search (Illinois
    // regula falsi, bisection while an end does not arrive) needs a few runs where bisection
    // needs twenty.
    bool met = false;
    physics::ControlProgram p_met;
    physics::SimulationResult sim_met;
    LambdaBracket root(
        [&](double x) {
          physics::ControlProgram p;
          physics::SimulationResult sim;
          const double fm = at(x, &p, &sim);
          if (std::abs(fm) <= tol_s) {
            met = true;
            p_met = std::move(p);
            sim_met = std::move(sim);
          }
          return fm;
        },
        a, fa, b, fb, 40);
    root.narrow([&] { return met; }, 1e-9);
    if (met) {
      run.program = std::move(p_met);
      run.sim = std::move(sim_met);
      run.cost_J = engine.energy_cost_J(run.sim);
      return used;
    }
  }
  return used;
}

// The trim at the engine's fine step, searched first on runs at kCoarseTrimStep_m (a fine run of
// a 48 km part is a million RK4 steps): the coarse runs' error is shifted by what the fine run
// of the program before the trim measures over the coarse one (a few milliseconds, nearly the
// same for a small move of one switch), and the program the coarse search finds is kept when
// its fine run meets tol_s; otherwise the search is done again on fine runs.
template <typename Error>
int trim_switch(const SectionEngine& engine, const EndCheck& arrives, LambdaRun& run, double lo_m,
                double hi_m, Error error, double tol_s, double max_trim_s = kMaxTrim_s) {
  const double fine_step_m = engine.options().resim_step_m;
  const double miss = std::abs(error(run.sim));
  if (miss <= tol_s || !(miss <= max_trim_s)) return 0;
  int used = 0;
  if (engine.searches_coarse(kCoarseTrimStep_m)) {
    LambdaRun coarse = run;
    coarse.sim = engine.resimulate(run.program, run.start, kCoarseTrimStep_m, {});
    ++used;
    const double bias_s = error(run.sim) - error(coarse.sim);
    if (finite(bias_s) && arrives(coarse.sim)) {
      auto shifted = [&](const physics::SimulationResult& sim) { return error(sim) + bias_s; };
      used += trim_switch_at(engine, arrives, coarse, lo_m, hi_m, shifted, 0.5 * tol_s, max_trim_s,
                             kCoarseTrimStep_m);
      const bool moved = !std::equal(
          coarse.program.begin(), coarse.program.end(), run.program.begin(), run.program.end(),
          [](const physics::ProgramStep& a, const physics::ProgramStep& b) {
            return a.from_m == b.from_m && a.control == b.control;
          });
      if (moved) {
        physics::SimulationResult sim = engine.resimulate(coarse.program, run.start, run.sim);
        ++used;
        if (arrives(sim) && std::abs(error(sim)) <= tol_s) {
          run.program = std::move(coarse.program);
          run.sim = std::move(sim);
          run.cost_J = engine.energy_cost_J(run.sim);
          return used;
        }
      }
    }
  }
  return used +
         trim_switch_at(engine, arrives, run, lo_m, hi_m, error, tol_s, max_trim_s, fine_step_m);
}

// One part's search for its prices. First the plain running-time search for the latest
// arrival (one price): if every passing window holds, that is the optimum (a non-binding
// window changes nothing). Otherwise the most missed passing window binds at its bound, and
// each binding point gets the price of the stretch that ends at it (from the binding point
// before it, or the start); the stretch after the last binding point has lambda_after. The
// outer search is on the price before a binding point for its passing time, the inner on
// lambda_after for the arrival. With one binding point that is one root search; with several,
// each price is searched for its own point's time in turn (the others held), cycling until
// every binding point is within the search's tolerance (coordinate-wise; a price moves its own
// point most, and the later points only by the same shift, which their own prices take back).
// A window still missed joins the binding set and the search is repeated. The arrival is a
// window too: when even the lowest price after the last binding point arrives before the
// latest arrival, the arrival does not bind and that run is kept. Speed windows missed by the
// run are added as speed bands at their stage, and the search is repeated with them.
class PartSolver {
 public:
  PartSolver(const SectionEngine& engine, const StartState& start, const EndCheck& end,
             double target_s, double earliest_arrival_s, std::vector<PartPoint> points,
             const std::vector<TimingWindow>& windows, const TimingJourneyOptions& options,
             bool bands_on_both_stages, bool arrival_free)
      : engine_(engine),
        start_(start),
        end_(end),
        target_s_(target_s),
        earliest_arrival_s_(earliest_arrival_s),
        arrival_free_(arrival_free),
        points_(std::move(points)),
        windows_(windows),
        options_(options),
        bands_on_both_stages_(bands_on_both_stages) {}

  int evaluations() const { return evaluations_; }
  // Whether every window of the part and its arrival hold on r's re-simulation, within the
  // tolerances the journey reports them met by (a zero-width one within kZeroWidthTime_s and
  // kZeroWidthSpeed_ms).
  bool every_window_holds(const LambdaRun& r) const {
    if (!end_(r.sim)) return false;
    const double tol_t = options_.time_tolerance_s;
    const double tol_v = units::kmh_to_ms(options_.speed_tolerance_kmh);
    auto time_tol = [&](double lo, double hi) {
      return lo == hi ? std::min(tol_t, kZeroWidthTime_s) : tol_t;
    };
    const double t_end = r.sim.running_time_s, te = time_tol(earliest_arrival_s_, target_s_);
    if (!(t_end <= target_s_ + te && t_end >= earliest_arrival_s_ - te)) return false;
    for (const PartPoint& p : points_) {
      const TimingWindow& w = windows_[p.index];
      const Passing at = passing_at(r.sim.trace, p.s_m);
      const double tt = time_tol(p.earliest_s, p.latest_s);
      const double tv =
          w.min_speed_ms == w.max_speed_ms ? std::min(tol_v, kZeroWidthSpeed_ms) : tol_v;
      if (!(at.t_s >= p.earliest_s - tt && at.t_s <= p.latest_s + tt &&
            at.v_ms >= w.min_speed_ms - tv && at.v_ms <= w.max_speed_ms + tv)) {
        return false;
      }
    }
    return true;
  }
  // Whether a speed window between two stages was banded on its transitions.
  bool banded_transitions() const {
    return std::any_of(bands_.begin(), bands_.end(),
                       [](const SpeedBand& b) { return b.at_fraction > 0.0; });
  }
  const std::vector<PartPoint>& points() const { return points_; }
  const std::vector<std::string>& notes() const { return notes_; }
  // The price of stretch k of the part (k = 0 .. points().size(): the stretch that ends at
  // point k, or at the arrival).
  double stretch_price(int k) const {
    for (std::size_t m = 0; m < binding_.size(); ++m) {
      if (k <= binding_[m]) return before_[m];
    }
    return lambda_after_;
  }
  // With several binding points, one that the others already keep well inside its window
  // (even its lowest price passes it early for a latest bound, late for an earliest one) does
  // not bind after all: its window is inactive at the optimum and is not reported as binding.
  bool inactive(std::size_t m) const { return m < inactive_.size() && inactive_[m]; }
  void mark_inactive(const LambdaRun& run) {
    inactive_.assign(binding_.size(), false);
    if (binding_.size() < 2) return;
    for (std::size_t m = 0; m < binding_.size(); ++m) {
      const PartPoint& p = points_[binding_[m]];
      const double t = passing_at(run.sim.trace, p.s_m).t_s;
      const double margin = 2.0 * inside_s(m) + options_.time_tolerance_s;
      inactive_[m] = finite(t) && t > p.earliest_s + margin && t < p.latest_s - margin;
    }
  }

  // How far inside its bound a binding passing point may pass (see search_target_s).
  // (0 once meet_bindings_exactly has put every binding point at its bound.)
  double binding_slack_s() const {
    if (binding_.size() < 2 || exact_) return 0.0;
    double slack = 0.0;
    for (std::size_t m = 0; m < binding_.size(); ++m) slack = std::max(slack, 2.0 * inside_s(m));
    return slack;
  }
  // The sign of point k's multiplier: +1 its latest bound binds (the price before it is the
  // higher), -1 its earliest, 0 it does not bind.
  int binding_sign(int k) const {
    for (std::size_t m = 0; m < binding_.size(); ++m) {
      if (binding_[m] != k || inactive(m)) continue;
      const double next = m + 1 < binding_.size() ? before_[m + 1] : lambda_after_;
      return before_[m] > next ? 1 : -1;
    }
    return 0;
  }

  // before: the price of the stretch ending at each binding point (empty: one price, after).
  StagePrices prices(const std::vector<double>& before, double after) const {
    StagePrices p;
    const int transitions = engine_.grid().stage_count() - 1;
    p.lambda_J_per_s.assign(transitions, after);
    int from = 0;
    for (std::size_t m = 0; m < before.size(); ++m) {
      const int upto = std::clamp(points_[binding_[m]].stage, 0, transitions);
      for (int i = from; i < upto; ++i) p.lambda_J_per_s[i] = before[m];
      from = std::max(from, upto);
    }
    p.bands = bands_;
    p.end_moving = end_.moving;
    p.end_min_ms = end_.min_ms;
    p.end_max_ms = end_.max_ms;
    return p;
  }

  // A search's evaluation: re-simulated at kSearchStep_m (RK4 at 0.5 m puts the times within
  // about a millisecond of the fine run's, at a tenth of its cost); the run kept is re-run at
  // the engine's fine step (fine) before anything is trimmed, checked or returned.
  LambdaRun evaluate(const std::vector<double>& before, double after) {
    ++evaluations_;
    report_progress(options_.progress, "price evaluation", evaluations_, 0);
    return engine_.run(prices(before, after), start_, engine_.search_step_m(kSearchStep_m));
  }
  LambdaRun fine(LambdaRun run) {
    if (!run.kept) return run;
    ++evaluations_;
    return engine_.fine_run(run);
  }

  // Signed miss of point k's time window: > 0 late, < 0 early, 0 inside.
  double time_miss_s(const LambdaRun& run, const PartPoint& p) const {
    const Passing at = passing_at(run.sim.trace, p.s_m);
    if (!finite(at.t_s)) return kInf;
    if (at.t_s > p.latest_s) return at.t_s - p.latest_s;
    if (at.t_s < p.earliest_s) return at.t_s - p.earliest_s;
    return 0.0;
  }
  bool speed_missed(const LambdaRun& run, const PartPoint& p) const {
    return speed_miss_ms(run, p) > units::kmh_to_ms(options_.speed_tolerance_kmh);
  }
  // How far outside p's speed window the run passes p (m/s; 0 inside, infinite when it never
  // reaches p).
  double speed_miss_ms(const LambdaRun& run, const PartPoint& p) const {
    const Passing at = passing_at(run.sim.trace, p.s_m);
    const TimingWindow& w = windows_[p.index];
    if (!finite(at.v_ms)) return kInf;
    return std::max({0.0, at.v_ms - w.max_speed_ms, w.min_speed_ms - at.v_ms});
  }
  double arrival_error_s(const LambdaRun& run) const {
    return end_(run.sim) ? run.sim.running_time_s - target_s_ : kInf;
  }

  // For fixed prices before the binding points (before empty: one price everywhere), the run
  // whose arrival is the latest allowed, or the slowest-priced run if even that arrives
  // earlier (the arrival then does not bind). ok: the arrival is within its window.
  struct Inner {
    LambdaRun run;
    double x_after = 0.0;
    bool ok = false;
  };
  // stop_s: the search ends at a run this close to the time (kArrivalTolerance_s unless the
  // caller trims more and checks), from x_after_guess_ with a first step of step (log price).
  Inner solve_arrival(const std::vector<double>& before, double stop_s = kArrivalTolerance_s,
                      double step = kFirstLogPriceStep) {
    Inner best;
    double best_abs = kInf;
    Inner floor_run;
    double floor_x = kInf;
    // A free arrival (arrival_free_): the latest early run that arrives, not before the
    // earliest arrival.
    Inner slowest;
    double slowest_s = -kInf;
    auto f = [&](double x) {
      const double after = std::exp(x);
      LambdaRun run = evaluate(before, after);
      const double err = arrival_error_s(run);
      if (finite(err) && std::abs(err) < best_abs) {
        best_abs = std::abs(err);
        best = {run, x, best_abs <= kMaxTrim_s};
      }
      if (arrival_free_ && finite(err) && err < 0.0 && run.sim.running_time_s > slowest_s &&
          run.sim.running_time_s >= earliest_arrival_s_ - options_.time_tolerance_s) {
        slowest_s = run.sim.running_time_s;
        slowest = {run, x, true};
      }
      if (finite(err) && err < 0.0 && x < floor_x) {
        floor_x = x;
        floor_run = {std::move(run), x, false};
      }
      return err;
    };
    falling_root(f, x_after_guess_, step, 0.0, 30.0, kInnerBudget, stop_s);
    if (!best.ok && slowest.ok) {
      // The part's latest arrival lies beyond the slowest run the grid solves reliably, and no
      // run came within reach of that run's time (the windows make the rest of the run faster,
      // or slower runs stall): the arrival does not bind, and the latest early run arrives
      // inside the window.
      best = std::move(slowest);
      arrival_at_floor_ = true;
    } else if (!best.ok && floor_x <= 1e-9) {
      // Too fast even at the lowest price: the arrival does not bind (if it is not too early).
      const double t = floor_run.run.sim.running_time_s;
      floor_run.ok = t >= earliest_arrival_s_ - options_.time_tolerance_s;
      best = std::move(floor_run);
      arrival_at_floor_ = true;
    } else {
      arrival_at_floor_ = false;
    }
    if (best.ok) x_after_guess_ = best.x_after;
    best.run = fine(std::move(best.run));
    return best;
  }

  // The last hundredths of the arrival by one switch point after from_m (when the arrival
  // binds: the run is not early by more than the search's tolerance).
  // If the run is still late by more than the window's tolerance (no switch after from_m can
  // make it faster, e.g. it coasts from before the last binding point to the stop), one switch
  // anywhere is moved: the binding points are then passed a little earlier, which their latest
  // bounds allow (an earliest bound is checked on the re-simulation like every window).
  void trim_arrival(LambdaRun& run, double from_m) {
    auto arrival = [&](const physics::SimulationResult& sim) {
      return sim.running_time_s - target_s_;
    };
    // (A run that ends moving is searched on the stage-priced sweep alone, whose running time
    // is more ragged: its trim takes any miss within kMaxTrim_s.)
    const double reach_s = end_.moving ? kMaxTrim_s : kArrivalTolerance_s;
    if (run.sim.running_time_s > target_s_ - reach_s) {
      evaluations_ += trim_switch(engine_, end_, run, from_m, engine_.route().length_m(), arrival,
                                  kTrimTolerance_s);
    }
    if (from_m > 0.0 && arrival(run.sim) > options_.time_tolerance_s) {
      evaluations_ += trim_switch(engine_, end_, run, 0.0, engine_.route().length_m(), arrival,
                                  kTrimTolerance_s);
    }
  }

  LambdaRun solve(bool* met) {
    LambdaRun run;
    bool ok = false;
    if (!end_.moving) {
      TimeSearchOptions search;
      search.progress = options_.progress;
      const TimeSearchResult plain = solve_for_time(engine_, target_s_, search, start_);
      evaluations_ += plain.iterations;
      run = plain.run;
      ok = plain.converged;
      lambda_after_ = run.lambda;
      x_after_guess_ = std::log(std::max(1.0, run.lambda));
    } else {
      // A run that ends moving: the plain search ends at rest, so the one price is searched
      // here, with the end's speed band (StagePrices::end_moving). Its trim takes any miss
      // within kMaxTrim_s, so the search first stops there: the last evaluations of a tighter
      // search bisect jumps of the ragged running time (on the GPOPS-II case 4 of 15, ending
      // 0.514 s from the time instead of 0.521 s). Only where that trim does not meet the time
      // is the price searched on, to kArrivalTolerance_s, from where the first search ended.
      auto search_and_trim = [&](double stop_s, double step) {
        Inner in = solve_arrival({}, stop_s, step);
        run = std::move(in.run);
        if (in.ok) trim_arrival(run, 0.0);
        return in;
      };
      Inner in = search_and_trim(kMaxTrim_s, kFirstLogPriceStep);
      if (in.ok && !arrival_at_floor_ &&
          !(std::abs(run.sim.running_time_s - target_s_) <= options_.time_tolerance_s)) {
        in = search_and_trim(kArrivalTolerance_s, kRetryLogPriceStep);
      }
      ok = in.ok;
      lambda_after_ = std::exp(in.x_after);
    }
    for (int round = 0; round < 2 + static_cast<int>(std::max<std::size_t>(1, binding_.size()));
         ++round) {
      // Speed windows the run misses become bands.
      bool new_band = false;
      std::vector<const PartPoint*> still_missed;  // banded, and missed all the same
      for (const auto& p : points_) {
        if (!speed_missed(run, p)) continue;
        const std::vector<SpeedBand> bands = bands_at(p);
        if (bands.empty()) continue;
        const bool banded = std::any_of(bands_.begin(), bands_.end(), [&](const SpeedBand& b) {
          return b.stage == bands.front().stage;
        });
        if (banded) {
          still_missed.push_back(&p);
        } else {
          bands_.insert(bands_.end(), bands.begin(), bands.end());
          new_band = true;
        }
      }
      // The most missed time window (a zero-width one is missed beyond half of kExactTime_s,
      // not half the window tolerance: passed 2 ms late, it did not bind and was reported
      // missed).
      int worst = -1;
      double worst_miss = 0.0;
      for (std::size_t k = 0; k < points_.size(); ++k) {
        const PartPoint& p = points_[k];
        const double m = std::abs(time_miss_s(run, p));
        const double limit =
            0.5 * (p.earliest_s == p.latest_s ? kExactTime_s : options_.time_tolerance_s);
        if (m > limit && m > worst_miss) worst = static_cast<int>(k), worst_miss = m;
      }
      // Only when every time window holds: a band narrowed while the prices still move (a
      // window missed by seconds) took the run into braking for nothing, 24 % above its witness.
      if (worst < 0 && !new_band) {
        for (const PartPoint* p : still_missed) new_band = narrow_band(run, *p) || new_band;
      }
      if (worst < 0 && !new_band) break;
      if (worst < 0 && binding_.empty()) {
        // Bands alone: one price, searched with them.
        Inner in = solve_arrival({});
        run = std::move(in.run);
        ok = in.ok;
        lambda_after_ = std::exp(in.x_after);
        if (ok) trim_arrival(run, 0.0);
        continue;
      }
      if (worst >= 0 && !add_binding(worst)) {
        ok = false;
        break;
      }
      // Each binding point binds at the bound its run misses (or the one it was given).
      for (std::size_t m = 0; m < binding_.size(); ++m) {
        const PartPoint& p = points_[binding_[m]];
        const double miss = time_miss_s(run, p);
        if (miss != 0.0) bound_s_[m] = miss > 0.0 ? p.latest_s : p.earliest_s;
      }
      if (!meet_bindings(run) && !stitch_after_failed_search(run)) {
        ok = false;
        break;
      }
      ok = true;
      // The last hundredths by switch points (first-order neutral at the optimum): for each
      // binding point in turn one between the binding point before it and it (later points
      // shift with it and are trimmed next), then one after the last for the arrival.
      double lo = 0.0;
      for (std::size_t m = 0; m < binding_.size(); ++m) {
        const double s_k = points_[binding_[m]].s_m, bound = bound_s_[m];
        if (binding_.size() == 1) {  // several: see search_target_s
          evaluations_ += trim_switch(
              engine_, end_, run, lo, s_k,
              [&](const physics::SimulationResult& sim) {
                return passing_at(sim.trace, s_k).t_s - bound;
              },
              kTrimTolerance_s);
        }
        lo = s_k;
      }
      trim_arrival(run, lo);
    }
    if (ok && binding_.size() == 1 && !end_.moving) close_gap(run);
    mark_inactive(run);
    if (ok && (!binding_.empty() || !bands_.empty())) meet_bindings_exactly(run);
    if (ok && !binding_.empty()) meet_missed_windows(run);
    if (!ok && (!binding_.empty() || !bands_.empty()) && repair_on_simulator(run)) ok = true;
    if (ok) {
      for (std::size_t m = 0; m < binding_.size(); ++m) {
        if (inactive(m)) continue;
        const PartPoint& p = points_[binding_[m]];
        const double off = std::abs(passing_at(run.sim.trace, p.s_m).t_s - bound_s_[m]);
        const double allowed =
            binding_.size() == 1 || exact_ ? options_.time_tolerance_s : 2.0 * inside_s(m) + 1e-9;
        // (A run outside the window is reported as missing it, on the re-simulation.)
        const double t = passing_at(run.sim.trace, p.s_m).t_s;
        const bool inside = t >= p.earliest_s - options_.time_tolerance_s &&
                            t <= p.latest_s + options_.time_tolerance_s;
        if (off > allowed && inside) {
          // Inside the window but not at the bound the unconstrained run missed: feasible, and
          // possibly not the least energy (the prices could not be set closer on this grid).
          notes_.push_back(format_text(
              "the price search for %s ended %.2f s from its %s bound: every window can hold, "
              "but the run may not be the least-energy one",
              point_name(p.index, windows_[p.index]).c_str(), off,
              bound_s_[m] == p.latest_s ? "latest" : "earliest"));
        }
        // A latest bound is held by a dearer second before the point, an earliest one by a
        // cheaper one; the other sign means the window need not bind (a multiplier < 0).
        const int sign = binding_sign(binding_[m]);
        if (binding_.size() > 1 && (sign > 0) != (bound_s_[m] == p.latest_s)) {
          notes_.push_back(format_text(
              "%s binds with a multiplier of the wrong sign: every window holds, but the run "
              "may not be the least-energy one",
              point_name(p.index, windows_[p.index]).c_str()));
        }
      }
    }
    if (end_.moving && end_.reaches_end(run.sim) && (ok || binding_.empty())) {
      // Also when the search ended more than kMaxTrim_s from the arrival: the trim here reaches
      // further, and the run is kept only as the windows check it on the re-simulation.
      meet_end_exactly(run);
      // What one switch at a time left of a moving end's time and zero-width speed (outside
      // what the window check allows) is closed jointly; a run that meets them is left as it
      // is (the cruise polish below starts from it).
      const bool time_met =
          arrival_at_floor_ || std::abs(run.sim.running_time_s - target_s_) <= kExactTime_s;
      const bool speed_met = end_.min_ms != end_.max_ms ||
                             std::abs(run.sim.end_speed_ms - end_.min_ms) <= kExactSpeed_ms;
      if (!(time_met && speed_met)) meet_bindings_exactly(run);
      if (!ok && binding_.empty() && end_(run.sim) &&
          std::abs(run.sim.running_time_s - target_s_) <= options_.time_tolerance_s) {
        ok = true;
      }
    }
    if (end_.moving && ok && binding_.empty() && bands_.empty() && end_(run.sim) &&
        std::abs(run.sim.running_time_s - target_s_) <= kTrimTolerance_s) {
      // The stage-priced search of a run that ends moving does not polish its cruise as the
      // plain search does: the same polish, with the final brake solved for the end speed when
      // the end's window has zero width. It only ever replaces the run by a cheaper one that
      // arrives within kTrimTolerance_s and ends inside the window.
      PolishEnd polish_end;
      polish_end.moving = true;
      polish_end.reaches = [this](const physics::SimulationResult& sim) { return end_(sim); };
      if (end_.max_ms - end_.min_ms <= 2.0 * end_.tol_ms) {
        polish_end.pinned_speed_ms = 0.5 * (end_.min_ms + end_.max_ms);
        polish_end.speed_tolerance_ms = end_.tol_ms;
      }
      CruisePolishOptions polish;
      polish.price_search_step_m = kPolishPriceStep_m;
      polish_cruise(engine_, target_s_, kTrimTolerance_s, polish, run, polish_end);
    }
    if (end_.moving && binding_.empty() && !arrival_at_floor_ && end_(run.sim) &&
        run.sim.running_time_s < target_s_ - options_.time_tolerance_s &&
        run.sim.running_time_s >= earliest_arrival_s_ - options_.time_tolerance_s) {
      // The running time of a run that ends moving can jump by seconds between neighbouring
      // prices (a slow approach to a low end speed): the search ends with a run inside the
      // arrival window but short of its latest bound. Feasible (every window is checked on the
      // re-simulation), possibly not the least energy.
      ok = true;
      notes_.push_back(format_text(
          "the arrival search ended %.2f s before the latest arrival: every window can hold, but "
          "the run may not be the least-energy one",
          target_s_ - run.sim.running_time_s));
    }
    *met = ok;
    return run;
  }

 private:
  // A run that ends moving, made to meet its end window exactly where the window asks for one
  // speed (min = max, within kExactSpeed_ms) and its arrival binds (within kExactTime_s): the
  // onset of the last braking phase is moved so the run ends at that speed (the end speed
  // rises as braking starts later), then a switch is trimmed for the time, and again, as each
  // moves the other a little (a switch near the end moves the time by milliseconds).
  void meet_end_exactly(LambdaRun& run) {
    const bool one_speed = end_.min_ms == end_.max_ms;
    auto arrival = [&](const physics::SimulationResult& sim) {
      return sim.running_time_s - target_s_;
    };
    for (int round = 0; round < 4; ++round) {
      if (one_speed) fix_end_speed(run, end_.min_ms);
      const double late = arrival(run.sim);
      // (The running time of a run that ends moving is ragged in its price by up to seconds:
      // the trim takes a miss of up to kMovingEndTrim_s.)
      const bool binds = !arrival_at_floor_ && std::abs(late) <= kMovingEndTrim_s;
      if (binds && std::abs(late) > kExactTime_s) {
        evaluations_ += trim_switch(engine_, end_, run, 0.0, engine_.route().length_m(), arrival,
                                    0.5 * kExactTime_s, kMovingEndTrim_s);
      }
      const bool time_ok = !binds || std::abs(arrival(run.sim)) <= kExactTime_s;
      const bool speed_ok =
          !one_speed || std::abs(run.sim.end_speed_ms - end_.min_ms) <= kExactSpeed_ms;
      if (time_ok && speed_ok) return;
    }
  }

  // Moves the onset of the program's last braking phase so the run ends at v_ms (bisection on
  // the re-simulated end speed); the run is left as it is when no onset reaches it. Bisection,
  // not the shared secant search (dp/lambda_bracket.hpp): an onset too late stops the run short
  // of the end, where the end speed has no finite value to draw a secant through.
  void fix_end_speed(LambdaRun& run, double v_ms) {
    if (std::abs(run.sim.end_speed_ms - v_ms) <= 0.5 * kExactSpeed_ms) return;
    const physics::ControlProgram program = run.program;
    const double length = engine_.route().length_m();
    std::size_t k = program.size();
    while (k > 1 && program[k - 1].control != physics::Control::MaxBrake) --k;
    if (k <= 1) return;
    const std::size_t b = k - 1;  // the last braking phase starts at program[b].from_m
    double lo = program[b - 1].from_m + 1e-6;
    double hi = (b + 1 < program.size() ? program[b + 1].from_m : length) - 1e-6;
    // End speed minus v_ms with the onset at x; -infinity for a run that stops short.
    auto at = [&](double x, physics::ControlProgram* p_out, physics::SimulationResult* s_out) {
      physics::ControlProgram p = program;
      p[b].from_m = x;
      physics::SimulationResult sim = engine_.resimulate(p, run.start, run.sim);
      ++evaluations_;
      const double e = end_.reaches_end(sim) ? sim.end_speed_ms - v_ms : -kInf;
      if (p_out) *p_out = std::move(p);
      if (s_out) *s_out = std::move(sim);
      return e;
    };
    if (!(hi > lo) || !(at(lo, nullptr, nullptr) <= 0.0) || !(at(hi, nullptr, nullptr) >= 0.0)) {
      return;
    }
    for (int it = 0; it < 60; ++it) {
      const double m = 0.5 * (lo + hi);
      physics::ControlProgram p;
      physics::SimulationResult sim;
      const double e = at(m, &p, &sim);
      if (std::abs(e) <= 0.5 * kExactSpeed_ms) {
        run.program = std::move(p);
        run.sim = std::move(sim);
        run.cost_J = engine_.energy_cost_J(run.sim);
        return;
      }
      (e < 0.0 ? lo : hi) = m;
    }
  }

  // One binding point of a part that ends at rest, its run stitched at the point: one switch
  // before the point is moved, however far, so the run passes at the bound (when its search
  // ended away from it: the passing time jumps between neighbouring prices, e.g. a stretch
  // priced so low that a coast appears or vanishes), and the rest of the run from there is
  // re-solved from the state it passes in for the time left (the plain search from a restart:
  // the optimum of the rest, whatever came before, with the cruise polish the stage-priced
  // sweep does not run). The stitched program is re-simulated from the start and kept when it
  // reaches its stop at the latest arrival and passes the point at its bound, and either the
  // run before missed a window (the point's or the arrival) or the stitched one costs less.
  // True when the run passes the point within the tolerance afterwards (also when it did
  // before).
  bool close_gap(LambdaRun& run) {
    const PartPoint& p = points_[binding_[0]];
    const double bound = bound_s_[0];
    const double s_k = p.s_m;
    const double off = passing_at(run.sim.trace, s_k).t_s - bound;
    if (!finite(off)) return false;
    const bool was_within = std::abs(off) <= options_.time_tolerance_s;
    LambdaRun trimmed = run;
    evaluations_ += trim_switch(
        engine_, end_, trimmed, 0.0, s_k,
        [&](const physics::SimulationResult& sim) {
          return passing_at(sim.trace, s_k).t_s - bound;
        },
        kTrimTolerance_s, std::abs(off) + kMaxTrim_s);
    const Passing at = passing_at(trimmed.sim.trace, s_k);
    if (!(std::abs(at.t_s - bound) <= kTrimTolerance_s) || !(at.v_ms > 0.0)) return was_within;
    TimeSearchResult rest;
    try {
      TimeSearchOptions search;
      search.progress = options_.progress;
      rest = solve_for_time(engine_, target_s_ - at.t_s, search, {s_k, at.v_ms});
    } catch (const TimeRequestError&) {
      return was_within;  // the time left is outside what the rest can run
    }
    evaluations_ += rest.iterations;
    // (A rest whose own trim stopped a few milliseconds short is still a rest: the stitched
    // run's arrival is trimmed below, and every window is checked.)
    const bool rest_near =
        run_arrives(rest.run.sim) &&
        std::abs(rest.run.sim.running_time_s - (target_s_ - at.t_s)) <= kArrivalTolerance_s;
    if (!rest.converged && !rest_near) return was_within;
    physics::ControlProgram stitched;
    for (const auto& step : trimmed.program) {
      if (step.from_m < s_k) stitched.push_back(step);
    }
    for (const auto& step : rest.run.program) {
      if (step.from_m >= s_k - 1e-9) stitched.push_back(step);
    }
    // The run as it is misses the window (early for an earliest bound, late for a latest one):
    // any feasible stitched run replaces it; otherwise only a cheaper one.
    // (So does a run that misses its arrival.)
    const bool run_misses =
        (off < 0.0 ? bound == p.earliest_s : bound == p.latest_s) || !end_(run.sim) ||
        !(std::abs(run.sim.running_time_s - target_s_) <= options_.time_tolerance_s);
    LambdaRun out = run;
    out.program = simplify_program(stitched, 0.0);
    out.sim = engine_.simulate(out.program, start_);
    ++evaluations_;
    out.cost_J = engine_.energy_cost_J(out.sim);
    const Passing now = passing_at(out.sim.trace, s_k);
    // (The rest is re-solved without the part's speed bands: a stitched run that misses a
    // window the run met is not kept.)
    if (!end_(out.sim) || !(std::abs(out.sim.running_time_s - target_s_) <= kArrivalTolerance_s) ||
        !(std::abs(now.t_s - bound) <= options_.time_tolerance_s) ||
        !(run_misses || out.cost_J < run.cost_J) || loses_a_window(run, out)) {
      return was_within;
    }
    trim_arrival(out, s_k);
    run = std::move(out);
    return true;
  }

  // Whether a passing window (time or speed, within the options' tolerances) that holds on
  // from's re-simulation is missed on to's, or a speed window from misses is missed by more.
  bool loses_a_window(const LambdaRun& from, const LambdaRun& to) const {
    auto holds = [&](const LambdaRun& r, const PartPoint& p) {
      return std::abs(time_miss_s(r, p)) <= options_.time_tolerance_s && !speed_missed(r, p);
    };
    const double tol_v = units::kmh_to_ms(options_.speed_tolerance_kmh);
    return std::any_of(points_.begin(), points_.end(), [&](const PartPoint& p) {
      return (holds(from, p) && !holds(to, p)) ||
             speed_miss_ms(to, p) > speed_miss_ms(from, p) + tol_v;
    });
  }

  // A banded speed window run still misses (the cruise it holds over the point, or the
  // sweep's interpolation between speeds, moved it out): p's bands (as bands_at gives them)
  // are narrowed on the missed side by the miss, keeping at least half of each. False when
  // they cannot narrow further.
  bool narrow_band(const LambdaRun& run, const PartPoint& p) {
    const std::vector<SpeedBand> of_p = bands_at(p);
    const Passing at = passing_at(run.sim.trace, p.s_m);
    const TimingWindow& w = windows_[p.index];
    bool narrowed = false;
    for (SpeedBand& b : bands_) {
      const bool mine = std::any_of(of_p.begin(), of_p.end(),
                                    [&](const SpeedBand& x) { return x.stage == b.stage; });
      if (!mine) continue;
      const double middle = 0.5 * (b.min_ms + b.max_ms);
      if (at.v_ms > w.max_speed_ms) {
        const double to = std::max(middle, b.max_ms - (at.v_ms - w.max_speed_ms));
        narrowed = narrowed || to < b.max_ms - 1e-9;
        b.max_ms = to;
      } else if (at.v_ms < w.min_speed_ms) {
        const double to = std::min(middle, b.min_ms + (w.min_speed_ms - at.v_ms));
        narrowed = narrowed || to > b.min_ms + 1e-9;
        b.min_ms = to;
      }
    }
    return narrowed;
  }

  // The price search for the one binding point of a part that ends at rest found no run that
  // also meets the arrival (on a coarse grid the arrival can jump by tens of seconds between
  // neighbouring prices after the point, e.g. CH_StGallen_Wil's feasible journey at --ds 10
  // --dv 0.5): the run is stitched at the point instead (close_gap: one switch before it moved
  // until the run passes at the bound, the rest re-solved by the plain search from there). The
  // stitched run keeps every window, checked on its re-simulation, but its passing speed is not
  // searched, so it is reported as possibly not the least-energy run. False when that fails too.
  bool stitch_after_failed_search(LambdaRun& run) {
    if (binding_.size() != 1 || end_.moving) return false;
    const PartPoint& p = points_[binding_[0]];
    const double bound = bound_s_[0];
    auto stitched = [&](LambdaRun r) -> std::optional<LambdaRun> {
      if (!close_gap(r)) return std::nullopt;
      const double t = passing_at(r.sim.trace, p.s_m).t_s;
      if (!(std::abs(t - bound) <= options_.time_tolerance_s) ||
          !(std::abs(r.sim.running_time_s - target_s_) <= options_.time_tolerance_s)) {
        return std::nullopt;
      }
      return r;
    };
    // The prefix from the price before the point alone, searched for its passing time (the
    // price after it held at the part's plain price; the arrival is the rest's re-solve), and
    // the run as it is: each stitched, the cheaper kept.
    LambdaRun priced;
    double priced_abs = kInf;
    falling_root(
        [&](double x) {
          LambdaRun r = evaluate({std::exp(x)}, lambda_after_);
          const double t = passing_at(r.sim.trace, p.s_m).t_s;
          if (!end_(r.sim) || !finite(t)) return kInf;
          if (std::abs(t - bound) < priced_abs) priced_abs = std::abs(t - bound), priced = r;
          return t - bound;
        },
        std::log(std::max(1.0, before_[0])), kFirstLogPriceStep, 0.0, 30.0, kOuterBudget,
        kPassingTolerance_s);
    std::optional<LambdaRun> best = stitched(run);
    if (priced_abs <= kMaxTrim_s) {
      std::optional<LambdaRun> other = stitched(fine(std::move(priced)));
      if (other && (!best || other->cost_J < best->cost_J)) best = std::move(other);
    }
    if (!best) return false;
    run = std::move(*best);
    drop_no_run_note(p);
    notes_.push_back(format_text(
        "the price search for %s found no run that also meets the arrival on this grid; the run "
        "is stitched at its bound (the rest re-solved from there): every window holds, but the "
        "run may not be the least-energy one",
        point_name(p.index, windows_[p.index]).c_str()));
    return true;
  }

  // The binding windows put at their bounds, jointly. The price search leaves each binding
  // point up to 2 inside_s inside its bound (search_target_s, several binding points) or the
  // arrival a few tenths from its time, and one switch per equation (trim_switch) cannot always
  // close them: with the points at their bounds the speed at the last one may leave the rest no
  // switch that sets the arrival. Here every residual (each binding point's passing time minus
  // its bound, the arrival minus the latest arrival when it binds, the end speed minus a
  // zero-width end speed window, a passing point's speed minus its zero-width speed window) is a
  // function of every switch position of the program, and they are zeroed together by Newton's
  // method on the switch positions (newton_on_switches). Small moves of switches are first-order
  // neutral in the cost at an optimum (its prices are the multipliers), so the run keeps its cost
  // to first order. A window of a passing point that the run (or a Newton result) still misses
  // on its re-simulation joins the residuals at its nearer bound, a quarter of its tolerance
  // inside: a speed band holds grid speeds at its stage, and the re-simulated run between two
  // stages can pass the point outside it by tenths of a km/h (bench/bench_timing_windows.cpp,
  // docs/ttobench.md "Random windows"). Far from its targets the solve goes by continuation,
  // and without the program's shortest phases when they pin its switches. The run is replaced
  // only when every window of the part holds on its re-simulation (holds_exactly); otherwise
  // the search's run stays. With hold_bindings false no binding point is held at its bound:
  // only the windows the run misses are (meet_missed_windows).
  void meet_bindings_exactly(LambdaRun& run, bool hold_bindings = true) {
    std::vector<std::size_t> active;
    for (std::size_t m = 0; m < binding_.size() && hold_bindings; ++m) {
      if (!inactive(m)) active.push_back(m);
    }
    const bool arrival_binds = !arrival_at_floor_;
    const bool pinned_end = end_.moving && end_.min_ms == end_.max_ms;
    const double tol_v = units::kmh_to_ms(options_.speed_tolerance_kmh);
    const double tol_t = options_.time_tolerance_s;
    // A passing point's time or speed held at a value, within scale.
    struct Target {
      const PartPoint* point;
      bool speed;
      double value, scale;
    };
    std::vector<Target> targets;
    auto binds = [&](const PartPoint& p) {
      return std::any_of(active.begin(), active.end(),
                         [&](std::size_t m) { return &points_[binding_[m]] == &p; });
    };
    // Zero-width speed windows (their speed band only holds the nearest grid speeds).
    for (const PartPoint& p : points_) {
      const TimingWindow& w = windows_[p.index];
      if (w.min_speed_ms == w.max_speed_ms && finite(w.min_speed_ms)) {
        targets.push_back({&p, true, w.min_speed_ms, 0.5 * kExactSpeed_ms});
      }
    }
    // The windows sim misses (beyond half their tolerance) that are not held yet; true when
    // one was added. (A window narrower than half a tolerance is held at its middle.)
    auto hold_missed = [&](const physics::SimulationResult& sim) {
      bool added = false;
      // (A window of zero width is held at its value: first within a quarter of the window
      // tolerance, then, from that round's run, within half what holds_exactly allows; one
      // solve straight to the tight scale stalled on runs a second away.)
      auto add = [&](const PartPoint& p, bool speed, double x, double lo, double hi, double tol,
                     double exact_tol) {
        const double missed_by = lo == hi ? exact_tol : 0.5 * tol;
        if (!finite(x) || !(x < lo - missed_by || x > hi + missed_by)) return;
        const auto held = std::find_if(targets.begin(), targets.end(), [&](const Target& t) {
          return t.point == &p && t.speed == speed;
        });
        if (held != targets.end()) {
          if (lo == hi && held->scale > 0.5 * exact_tol)
            held->scale = 0.5 * exact_tol, added = true;
          return;
        }
        const double in = std::min(0.25 * tol, 0.5 * (hi - lo));
        targets.push_back({&p, speed, x > hi ? hi - in : lo + in, 0.25 * tol});
        added = true;
      };
      for (const PartPoint& p : points_) {
        const TimingWindow& w = windows_[p.index];
        const Passing at = passing_at(sim.trace, p.s_m);
        add(p, true, at.v_ms, w.min_speed_ms, w.max_speed_ms, tol_v, kExactSpeed_ms);
        if (!binds(p)) add(p, false, at.t_s, p.earliest_s, p.latest_s, tol_t, kTrimTolerance_s);
      }
      return added;
    };
    // Residuals scaled by their tolerances (kTrimTolerance_s, 0.5 kExactSpeed_ms, a target's).
    auto residuals = [&](const physics::SimulationResult& sim, std::vector<double>& r) {
      r.clear();
      for (std::size_t m : active) {
        const double t = passing_at(sim.trace, points_[binding_[m]].s_m).t_s;
        r.push_back((t - bound_s_[m]) / kTrimTolerance_s);
      }
      if (arrival_binds) r.push_back((sim.running_time_s - target_s_) / kTrimTolerance_s);
      if (pinned_end) r.push_back((sim.end_speed_ms - end_.min_ms) / (0.5 * kExactSpeed_ms));
      for (const Target& x : targets) {
        const Passing at = passing_at(sim.trace, x.point->s_m);
        r.push_back(((x.speed ? at.v_ms : at.t_s) - x.value) / x.scale);
      }
      bool ok = end_.reaches_end(sim);
      for (double v : r) ok = ok && finite(v);
      return ok;
    };
    hold_missed(run.sim);
    LambdaRun from = run;  // each round starts from the last round's run
    for (int attempt = 0; attempt < kMissedWindowRounds; ++attempt) {
      std::vector<double> r;
      if (!residuals(from.sim, r) || r.empty()) return;
      if (attempt == 0 && max_abs(r) <= 1.0) {
        // Within every residual's scale; a zero-width window held at its first, loose scale
        // may still be missed (a run 7 ms off one): it is then tightened and solved for.
        if (holds_exactly(from, active, arrival_binds) || !hold_missed(from.sim) ||
            !residuals(from.sim, r) || max_abs(r) <= 1.0) {
          exact_ = true;
          return;
        }
      }
      std::optional<LambdaRun> cand = newton_or_continued(from, residuals);
      if (!cand) cand = newton_without_short_phases(from, residuals);
      if (!cand) cand = newton_with_split_phases(from, residuals);
      if (!cand) return;
      cand->cost_J = engine_.energy_cost_J(cand->sim);
      if (holds_exactly(*cand, active, arrival_binds)) {
        run = std::move(*cand);
        exact_ = true;
        return;
      }
      if (!hold_missed(cand->sim)) return;
      from = std::move(*cand);
    }
  }

  // A phase a few metres long between two switches pins both (each switch's weight is its
  // room, and switches may not cross), so a window that needs the phase moved by tens of metres
  // (a short hold after the first traction, a point near the flat-out time) is out of reach:
  // the program without its phases shorter than kShortPhase_m (the control before each runs on)
  // is solved by continuation instead.
  template <typename Residuals>
  std::optional<LambdaRun> newton_without_short_phases(const LambdaRun& run, Residuals& residuals) {
    LambdaRun merged = run;
    merged.program = simplify_program(run.program, kShortPhase_m);
    if (merged.program.size() == run.program.size()) return std::nullopt;
    merged.sim = engine_.simulate(merged.program, start_);
    ++evaluations_;
    return newton_or_continued(merged, residuals);
  }

  // One phase that runs through two timed points cannot pass both at their bounds: its own
  // switches move both passing times together (a hold at 67.89 km/h through a latest bound at
  // 372.7 m and a zero-width time 583.8 m on, passed 136 ms early, needs a slower hold between
  // them, a step below the grid's 0.5 km/h: bench_timing_windows /1/22 journey 28). The phase
  // is split after each timed point but its last by a short phase of another control, which
  // gives Newton's method the switch it lacks: a coast first (a hold inside a coast), then
  // traction (a hold inside traction); which way each moves the next passing time depends on
  // the phase and the gradient, so both are tried and the first run solved is kept. One Newton
  // solve each, without continuation: by continuation the split programs of a run that no split
  // helps cost a random-window test 38 s more.
  template <typename Residuals>
  std::optional<LambdaRun> newton_with_split_phases(const LambdaRun& run, Residuals& residuals) {
    using physics::Control;
    std::vector<double> timed;  // the points with a time window, in order
    for (const PartPoint& p : points_) {
      if (finite(p.earliest_s) || finite(p.latest_s)) timed.push_back(p.s_m);
    }
    std::sort(timed.begin(), timed.end());
    const double length = engine_.route().length_m();
    for (const Control inserted : {Control::Coast, Control::MaxTraction}) {
      physics::ControlProgram split;
      const physics::ControlProgram& prog = run.program;
      for (std::size_t k = 0; k < prog.size(); ++k) {
        split.push_back(prog[k]);
        const double end_m = k + 1 < prog.size() ? prog[k + 1].from_m : length;
        const Control c = prog[k].control;
        if (c == Control::MaxBrake) continue;
        const Control other = c == inserted ? Control::Hold : inserted;
        for (std::size_t i = 0; i + 1 < timed.size(); ++i) {
          if (!(timed[i] > prog[k].from_m && timed[i + 1] < end_m)) continue;
          const double gap_m = std::min(kSplitPhase_m, 0.25 * (timed[i + 1] - timed[i]));
          split.push_back({timed[i] + gap_m, other});
          split.push_back({timed[i] + 2.0 * gap_m, c});
        }
      }
      if (split.size() == prog.size()) return std::nullopt;
      LambdaRun cand = run;
      cand.program = std::move(split);
      cand.sim = engine_.simulate(cand.program, start_);
      ++evaluations_;
      if (std::optional<LambdaRun> solved = newton_on_switches(cand, residuals)) return solved;
    }
    return std::nullopt;
  }

  // One Newton solve on run's switches, and by continuation when that stalls.
  template <typename Residuals>
  std::optional<LambdaRun> newton_or_continued(const LambdaRun& run, Residuals& residuals) {
    std::optional<LambdaRun> cand = newton_on_switches(run, residuals);
    if (!cand) cand = continued_newton(run, residuals);
    return cand;
  }

  // Newton's method from far (a run seconds from its bounds, where one Newton solve's line
  // search stalls on the simulator's nonlinearity): the residuals are moved to 0 in steps, each
  // solve starting from the last one's run (continuation: at step a the residuals less (1 - a)
  // times the run's own are zeroed, so a = 0 is the run itself). A step that fails is halved,
  // down to a sixteenth; one that succeeds is doubled, up to a half.
  template <typename Residuals>
  std::optional<LambdaRun> continued_newton(const LambdaRun& run, Residuals& residuals) {
    std::vector<double> r0;
    if (!residuals(run.sim, r0)) return std::nullopt;
    LambdaRun at = run;
    double a = 0.0, step = 0.25;
    std::vector<double> jac;
    while (a < 1.0) {
      const double next = std::min(1.0, a + step);
      auto part = [&](const physics::SimulationResult& sim, std::vector<double>& r) {
        const bool ok = residuals(sim, r);
        if (ok) {
          for (std::size_t i = 0; i < r.size() && i < r0.size(); ++i) r[i] -= (1.0 - next) * r0[i];
        }
        return ok;
      };
      std::optional<LambdaRun> cand = newton_on_switches(at, part, &jac);
      if (cand) {
        at = std::move(*cand);
        a = next;
        step = std::min(0.5, 2.0 * step);
      } else if ((step *= 0.5) < 1.0 / 16.0) {
        return std::nullopt;
      }
    }
    return at;
  }

  // The Jacobian (q x u, row-major) of the residuals r of run over its program's switches (entry
  // 0 of the program is the start), by forward differences (backward where a switch cannot move
  // forward), one re-simulation per switch resumed where the programs agree; a column a
  // re-simulation gives no residuals for is left at 0 (that switch is not used).
  template <typename Residuals>
  std::vector<double> switch_jacobian(const LambdaRun& run, Residuals& residuals,
                                      const std::vector<double>& r) {
    constexpr double kStep_m = 0.5;
    const physics::ControlProgram& prog = run.program;
    const std::size_t n = prog.size(), q = r.size(), u = n - 1;
    const double length = engine_.route().length_m();
    std::vector<double> jac(q * u, 0.0), rk;
    for (std::size_t c = 0; c < u; ++c) {
      const std::size_t k = c + 1;
      const double next = k + 1 < n ? prog[k + 1].from_m : length;
      const double h = prog[k].from_m + kStep_m < next ? kStep_m : -kStep_m;
      if (prog[k].from_m + h <= prog[k - 1].from_m) continue;
      physics::ControlProgram p = prog;
      p[k].from_m += h;
      const physics::SimulationResult sim = engine_.resimulate(p, run.start, run.sim);
      ++evaluations_;
      if (!residuals(sim, rk)) continue;
      for (std::size_t i = 0; i < q; ++i) jac[i * u + c] = (rk[i] - r[i]) / h;
    }
    return jac;
  }

  // Newton's method on the switch positions of run's program for residuals(sim, r) = 0 (each
  // scaled so that |r_i| <= 1 is met): the Jacobian by finite differences on the simulator
  // (switch_jacobian), the step of least weighted length that zeroes the linear model
  // (W J^T (J W J^T)^-1 r, W: each switch's room, squared), halved while it does not lower the
  // largest residual or would reorder the switches. After a step the Jacobian is updated by
  // Broyden's rank-one formula (a run has 20-80 switches, each difference a re-simulation) and
  // differenced again only when the updated one gives no step; two steps on fresh differences
  // that each take off less than a tenth of the largest residual end the solve (a kink of the
  // simulator: such solves spent thousands of re-simulations without converging). The run that
  // meets every residual, or nullopt.
  template <typename Residuals>
  std::optional<LambdaRun> newton_on_switches(const LambdaRun& run, Residuals& residuals,
                                              std::vector<double>* jac_io = nullptr) {
    std::vector<double> r;
    if (!residuals(run.sim, r)) return std::nullopt;
    LambdaRun cand = run;
    const double length = engine_.route().length_m();
    constexpr double kMaxRoom_m = 50.0;  // a switch's weight stops growing with its room
    // J (q x u) of the current run, or a Broyden update of one; the caller's (jac_io) when it
    // passes one: a continuation's solves differ by constants in their residuals, not in their
    // Jacobian.
    std::vector<double> own;
    std::vector<double>& jac = jac_io != nullptr ? *jac_io : own;
    bool fresh = false;  // jac is the finite differences of the current run
    int jacobians = 0, stalls = 0;
    for (int iter = 0; iter < kBroydenIterations && max_abs(r) > 1.0; ++iter) {
      const physics::ControlProgram& prog = cand.program;
      const std::size_t n = prog.size();
      std::vector<std::size_t> sw;  // the program's switches (entry 0 is the start)
      for (std::size_t k = 1; k < n; ++k) sw.push_back(k);
      const std::size_t q = r.size(), u = sw.size();
      if (u == 0) return std::nullopt;
      if (jac.size() != q * u) jac.clear();
      if (jac.empty()) {
        if (jacobians == kNewtonIterations) break;
        jac = switch_jacobian(cand, residuals, r);
        fresh = true;
        ++jacobians;
      }
      // y = (J J^T + eps I)^-1 r, dx = -J^T y.
      // Weighted by each switch's room (the shorter of the phases on either side, squared):
      // a switch between two long phases takes the move, one that bounds a short phase hardly
      // moves, so the step keeps the switches in order.
      std::vector<double> wt(u, 0.0);
      for (std::size_t c = 0; c < u; ++c) {
        const std::size_t k = sw[c];
        const double next = k + 1 < n ? prog[k + 1].from_m : length;
        const double room =
            std::min({prog[k].from_m - prog[k - 1].from_m, next - prog[k].from_m, kMaxRoom_m});
        wt[c] = room * room;
      }
      std::vector<double> a(q * q, 0.0), y = r;
      for (std::size_t i = 0; i < q; ++i) {
        for (std::size_t j = 0; j < q; ++j) {
          for (std::size_t c = 0; c < u; ++c) {
            a[i * q + j] += jac[i * u + c] * wt[c] * jac[j * u + c];
          }
        }
      }
      double diag = 0.0;
      for (std::size_t i = 0; i < q; ++i) diag = std::max(diag, a[i * q + i]);
      for (std::size_t i = 0; i < q; ++i) a[i * q + i] += 1e-12 * diag;
      if (!(diag > 0.0) || !solve_dense(a, y, q)) {
        if (fresh) return std::nullopt;
        jac.clear();  // an updated Jacobian gone singular: differences again
        continue;
      }
      std::vector<double> dx(u, 0.0);
      for (std::size_t c = 0; c < u; ++c) {
        for (std::size_t i = 0; i < q; ++i) dx[c] -= wt[c] * jac[i * u + c] * y[i];
      }
      // The step, halved while the switches would cross or the residual does not fall.
      const double before = max_abs(r);
      bool moved = false;
      for (double f = 1.0; f > 1e-3 && !moved; f *= 0.5) {
        std::vector<double> step(u);
        for (std::size_t c = 0; c < u; ++c) step[c] = f * dx[c];
        physics::ControlProgram p = prog;
        bool ordered = true;
        for (std::size_t c = 0; c < u; ++c) p[sw[c]].from_m += step[c];
        for (std::size_t k = 1; k < n && ordered; ++k) {
          const double next = k + 1 < n ? p[k + 1].from_m : length;
          ordered = p[k].from_m > p[k - 1].from_m + 1e-6 && p[k].from_m < next - 1e-6;
        }
        if (!ordered) continue;
        physics::SimulationResult sim = engine_.resimulate(p, cand.start, cand.sim);
        ++evaluations_;
        std::vector<double> rn;
        if (!residuals(sim, rn) || !(max_abs(rn) < before)) continue;
        // Broyden's update of J for the step taken: J += (dr - J s) s^T / (s^T s).
        double ss = 0.0;
        for (std::size_t c = 0; c < u; ++c) ss += step[c] * step[c];
        for (std::size_t i = 0; i < q && ss > 0.0; ++i) {
          double js = 0.0;
          for (std::size_t c = 0; c < u; ++c) js += jac[i * u + c] * step[c];
          const double g = (rn[i] - r[i] - js) / ss;
          for (std::size_t c = 0; c < u; ++c) jac[i * u + c] += g * step[c];
        }
        cand.program = std::move(p);
        cand.sim = std::move(sim);
        r = std::move(rn);
        moved = true;
      }
      if (moved) {
        // Steps on fresh differences that each take off less than a tenth of the largest
        // residual: the solve is stuck on a kink of the simulator, not converging.
        if (fresh) stalls = max_abs(r) > kNewtonStall * before ? stalls + 1 : 0;
        if (stalls == kNewtonStalls) break;
        fresh = false;
      } else if (fresh) {
        return std::nullopt;
      } else {
        jac.clear();  // the updated Jacobian led nowhere: differences again
      }
    }
    if (!(max_abs(r) <= 1.0)) return std::nullopt;
    return cand;
  }

  // The searched run still misses a window after the joint Newton step on its binding points
  // (which holds them all at their bounds, also one whose multiplier came out of the wrong sign
  // and need not bind): it is moved onto the windows it misses alone, the binding points free
  // inside their windows, and kept only when every window then holds on its re-simulation, as
  // a feasible run that may not be the least-energy one.
  void meet_missed_windows(LambdaRun& run) {
    if (every_window_holds(run)) return;
    LambdaRun moved = run;
    meet_bindings_exactly(moved, false);
    if (!every_window_holds(moved)) return;
    run = std::move(moved);
    notes_.push_back(
        "the run the price search ended with missed a window; it is moved onto the windows by "
        "its switch points: every window holds, but the run may not be the least-energy one");
  }

  // The price search ended without a run that meets every window (on a coarse grid a passing
  // time near the flat-out one, or a speed window with it, jumps between neighbouring prices):
  // the run it ended with is moved onto the windows on the simulator instead
  // (meet_bindings_exactly: the binding points at their bounds, the arrival at its latest when
  // it binds, every window the run misses held a little inside). Kept only when every window
  // of the part holds on its re-simulation: feasible, and reported as possibly not the
  // least-energy run. False when that fails too.
  bool repair_on_simulator(LambdaRun& run) {
    if (!end_.reaches_end(run.sim)) return false;
    LambdaRun repaired = run;
    meet_bindings_exactly(repaired);
    if (!holds_exactly(repaired, {}, false)) {
      // Then with the binding points free inside their windows (meet_missed_windows).
      repaired = run;
      meet_bindings_exactly(repaired, false);
      if (!holds_exactly(repaired, {}, false)) return false;
    }
    run = std::move(repaired);
    for (const PartPoint& p : points_) drop_no_run_note(p);
    notes_.push_back(
        "the price search found no run that meets every window on this grid; its last run is "
        "moved onto the windows by its switch points: every window holds, but the run may not "
        "be the least-energy one");
    return true;
  }

  // The bands that hold p's speed window in the sweep: on the nodes of p's stage when p lies on
  // it, else on the transitions out of the stage before p, at p (SpeedBand::at_fraction). With
  // bands_on_both_stages_ a point between two stages is banded on the nodes of both instead:
  // stricter than the window (a run coasting up a rise through it passes the stage before it
  // above the window's top), but a run between them is monotone, so every run it allows
  // passes inside (solve_part's second try). A window narrower than the grid's speed step may
  // hold no node: it is widened by the step either side, and its last part closed on the
  // simulator (meet_bindings_exactly). None at the part's first and last stages.
  std::vector<SpeedBand> bands_at(const PartPoint& p) const {
    const StageGrid& grid = engine_.grid();
    const int last = grid.stage_count() - 1;
    const TimingWindow& w = windows_[p.index];
    const double dv = grid.dv_ms();
    const bool narrow = w.max_speed_ms - w.min_speed_ms < dv;
    const double lo = narrow ? w.min_speed_ms - dv : w.min_speed_ms;
    const double hi = narrow ? w.max_speed_ms + dv : w.max_speed_ms;
    const double off_m = p.s_m - grid.position(p.stage);
    const int other = p.stage + (off_m > 0.0 ? 1 : -1);
    std::vector<SpeedBand> out;
    if (std::abs(off_m) <= 1e-6 || bands_on_both_stages_) {
      if (p.stage <= 0 || p.stage >= last) return out;
      out.push_back({p.stage, lo, hi, 0.0});
      if (std::abs(off_m) > 1e-6 && other > 0 && other < last) out.push_back({other, lo, hi, 0.0});
      return out;
    }
    const int before = std::min(p.stage, other);
    if (before < 0 || before >= last) return out;
    const double f =
        (p.s_m - grid.position(before)) / (grid.position(before + 1) - grid.position(before));
    out.push_back({before, lo, hi, f});
    return out;
  }

  // Whether every window of the part holds on r's re-simulation, the binding points in active
  // at their bounds and the arrival (when it binds) at its latest, within kTrimTolerance_s.
  bool holds_exactly(const LambdaRun& r, const std::vector<std::size_t>& active,
                     bool arrival_binds) const {
    if (!end_(r.sim)) return false;
    const double late = r.sim.running_time_s - target_s_;
    if (arrival_binds
            ? !(std::abs(late) <= kTrimTolerance_s)
            : !(late <= options_.time_tolerance_s &&
                r.sim.running_time_s >= earliest_arrival_s_ - options_.time_tolerance_s)) {
      return false;
    }
    for (std::size_t m : active) {
      const double t = passing_at(r.sim.trace, points_[binding_[m]].s_m).t_s;
      if (!(std::abs(t - bound_s_[m]) <= kTrimTolerance_s)) return false;
    }
    const double tol_v = units::kmh_to_ms(options_.speed_tolerance_kmh);
    for (const PartPoint& p : points_) {
      const TimingWindow& w = windows_[p.index];
      const Passing at = passing_at(r.sim.trace, p.s_m);
      const double tt = w.earliest_s == w.latest_s ? kTrimTolerance_s : options_.time_tolerance_s;
      const double tv = w.min_speed_ms == w.max_speed_ms ? 0.5 * kExactSpeed_ms : tol_v;
      if (!finite(at.t_s) || at.t_s < p.earliest_s - tt || at.t_s > p.latest_s + tt ||
          at.v_ms < w.min_speed_ms - tv || at.v_ms > w.max_speed_ms + tv) {
        return false;
      }
    }
    return true;
  }

  // Adds points_[k] to the binding set (kept in order along the part), its price starting at
  // the price its stretch has now, so the prices do not change. False (with a note) when the
  // point shares its grid stage with a binding point (no price can part them).
  bool add_binding(int k) {
    if (std::find(binding_.begin(), binding_.end(), k) != binding_.end()) return true;
    for (int b : binding_) {
      if (points_[b].stage == points_[k].stage) {
        notes_.push_back(format_text(
            "%s and %s lie on one grid stage: their windows cannot both be priced (use a finer "
            "--ds)",
            point_name(points_[b].index, windows_[points_[b].index]).c_str(),
            point_name(points_[k].index, windows_[points_[k].index]).c_str()));
        return false;
      }
    }
    const double price = stretch_price(k);
    const auto at = std::lower_bound(binding_.begin(), binding_.end(), k) - binding_.begin();
    binding_.insert(binding_.begin() + at, k);
    before_.insert(before_.begin() + at, price);
    bound_s_.insert(bound_s_.begin() + at, 0.0);
    return true;
  }

  // The note of a price search that found no run meeting point p.
  std::string no_run_note(const PartPoint& p) const {
    return format_text("the price search for %s found no run that meets it",
                       point_name(p.index, windows_[p.index]).c_str());
  }
  // The search's "found no run" note for p gives way to what was done instead.
  void drop_no_run_note(const PartPoint& p) {
    const auto no_run = std::find(notes_.begin(), notes_.end(), no_run_note(p));
    if (no_run != notes_.end()) notes_.erase(no_run);
  }

  // The price before binding point m searched for its passing time, the others held; run and
  // the prices are set to the best run found. False (with a note) when no run meets it.
  bool search_price(std::size_t m, LambdaRun& run) {
    const PartPoint& p = points_[binding_[m]];
    const double bound = search_target_s(m);
    LambdaRun best;
    double best_abs = kInf;
    bool best_ok = false;
    double best_before = 0.0, best_after = 0.0;
    std::vector<double> before = before_;
    auto g = [&](double x) {
      before[m] = std::exp(x);
      Inner in = solve_arrival(before);
      const Passing at = passing_at(in.run.sim.trace, p.s_m);
      if (!in.ok || !finite(at.t_s)) return kInf;
      const double err = at.t_s - bound;
      if (std::abs(err) < best_abs) {
        best_abs = std::abs(err);
        best = std::move(in.run);
        best_ok = true;
        best_before = std::exp(x);
        best_after = std::exp(in.x_after);
      }
      return err;
    };
    falling_root(g, std::log(std::max(1.0, before_[m])), kFirstLogPriceStep, 0.0, 30.0,
                 kOuterBudget, passing_tolerance_s(m));
    if (!best_ok) {
      notes_.push_back(no_run_note(p));
      return false;
    }
    run = std::move(best);
    before_[m] = best_before;
    lambda_after_ = best_after;
    return true;
  }

  // With several binding points, no switch-point trim closes their last tenths (a switch
  // between two of them changes the speed at the later one, and the run after it by seconds),
  // so each is searched for a time inside_s(m) inside its bound, within inside_s(m): it passes
  // within 2 inside_s(m) of its bound, inside its window, and meet_bindings_exactly puts it at
  // its bound. inside_s is kInside_s, or a share of the stretch's time before the point when
  // that is more (kInsidePerStretch): over a long stretch the passing time is a step function of
  // the price with steps of tenths of a second (a cruise's speed is a grid speed: 0.2 km/h on
  // 12 km at 130 km/h is 0.5 s), and a search for 0.1 s there cycled through thousands of runs
  // (a 48.5 km journey with three timing points, 3 784 price evaluations; docs/ttobench.md).
  // One binding point: at its bound, within kPassingTolerance_s, and trimmed.
  double inside_s(std::size_t m) const {
    if (binding_.size() == 1) return 0.0;
    if (!long_part()) return kInside_s;
    const double from = m == 0 ? 0.0 : bound_s_[m - 1];
    return std::max(kInside_s, kInsidePerStretch * (bound_s_[m] - from));
  }
  // A part of at least kLongPart_m, where a run costs tenths of a second: its prices for
  // several binding points are searched by meet_bindings_gauss_seidel first, and its stretches'
  // passing tolerances grow with their time (inside_s). On shorter parts the search of
  // meet_bindings alone was checked on 240 random journeys (bench/bench_timing_windows.cpp);
  // there the Gauss-Seidel search first made two of them 3-4 % dearer (docs/ttobench.md).
  bool long_part() const { return engine_.route().length_m() >= kLongPart_m; }
  double search_target_s(std::size_t m) const {
    if (binding_.size() == 1) return bound_s_[m];
    const PartPoint& p = points_[binding_[m]];
    return bound_s_[m] == p.latest_s ? bound_s_[m] - inside_s(m) : bound_s_[m] + inside_s(m);
  }
  double passing_tolerance_s(std::size_t m) const {
    return binding_.size() == 1 ? kPassingTolerance_s : inside_s(m);
  }

  // Several binding points: each price searched for its own point's time with every other
  // price held, the price after the last binding point included (searched for the arrival), in
  // order along the part, cycling until every point and the arrival are within their
  // tolerances (Gauss-Seidel). Unlike search_price, no search re-solves the arrival at each of
  // its evaluations, so a search costs a few runs, not a few dozen, and sees the passing time
  // as a function of its own price alone. True also when a cycle moves no price and every
  // target is within kGaussSeidelAccept_s (see below); false (prices and run as they were) when
  // the cycles end otherwise.
  bool meet_bindings_gauss_seidel(LambdaRun& run) {
    const std::size_t k = binding_.size();
    const std::vector<double> before0 = before_;
    const double after0 = lambda_after_, guess0 = x_after_guess_;
    auto time_at = [&](const LambdaRun& r, std::size_t m) {
      return m < k ? passing_at(r.sim.trace, points_[binding_[m]].s_m).t_s : r.sim.running_time_s;
    };
    auto target = [&](std::size_t m) { return m < k ? search_target_s(m) : target_s_; };
    auto tolerance = [&](std::size_t m) {
      return m < k ? passing_tolerance_s(m) : kArrivalTolerance_s;
    };
    auto within = [&](const LambdaRun& r, std::size_t m) {
      const double t = time_at(r, m);
      if (m == k && end_(r.sim) && lambda_after_ <= 1.0 + 1e-9 && t < target_s_ &&
          t >= earliest_arrival_s_ - options_.time_tolerance_s) {
        return true;  // even the lowest price after the last point is early: it does not bind
      }
      return finite(t) && std::abs(t - target(m)) <= tolerance(m);
    };
    LambdaRun current = evaluate(before_, lambda_after_);
    for (int cycle = 0; cycle < kGaussSeidelCycles; ++cycle) {
      bool moved = false;
      for (std::size_t m = 0; m <= k; ++m) {
        if (within(current, m)) continue;
        std::optional<LambdaRun> best;
        double best_abs = kInf, best_x = 0.0;
        auto g = [&](double x) {
          std::vector<double> before = before_;
          double after = lambda_after_;
          (m < k ? before[m] : after) = std::exp(x);
          LambdaRun r = evaluate(before, after);
          const double t = m < k || end_(r.sim) ? time_at(r, m) : kInf;
          if (!finite(t)) return kInf;
          const double err = t - target(m);
          if (std::abs(err) < best_abs) best_abs = std::abs(err), best_x = x, best = std::move(r);
          return err;
        };
        const double x0 = std::log(std::max(1.0, m < k ? before_[m] : lambda_after_));
        falling_root(g, x0, kGaussSeidelLogStep, 0.0, 30.0, kGaussSeidelBudget, tolerance(m));
        if (!best) continue;
        double& price = m < k ? before_[m] : lambda_after_;
        moved = moved || std::abs(std::log(price) - best_x) > kNarrowestLogPrice;
        price = std::exp(best_x);
        current = std::move(*best);
      }
      bool all = true;
      for (std::size_t m = 0; m <= k; ++m) all = all && within(current, m);
      // A cycle that moved no price ends the search: each point is then as near its target as
      // its own price can put it (the time jumps across the target between neighbouring
      // prices). It is kept when every point is within kGaussSeidelAccept_s: the Newton step on
      // the switch points (meet_bindings_exactly) closes such gaps.
      bool near = !moved;
      for (std::size_t m = 0; m <= k && near; ++m) {
        near =
            within(current, m) || std::abs(time_at(current, m) - target(m)) <= kGaussSeidelAccept_s;
      }
      if (all || near) {
        x_after_guess_ = std::log(std::max(1.0, lambda_after_));
        arrival_at_floor_ = lambda_after_ <= 1.0 + 1e-9 &&
                            current.sim.running_time_s < target_s_ - kArrivalTolerance_s;
        run = fine(std::move(current));
        return true;
      }
      if (!moved) break;
    }
    before_ = before0;
    lambda_after_ = after0;
    x_after_guess_ = guess0;
    return false;
  }

  // Every binding point's price searched for its time: one root search for one point; for
  // several, cycles of one search per point with the others held (meet_bindings_gauss_seidel),
  // and when they do not meet every target, cycles of one search per point with the arrival
  // re-solved at each of its evaluations (skipping those already within the tolerance) until
  // all are within it.
  bool meet_bindings(LambdaRun& run) {
    const std::size_t k = binding_.size();
    if (k > 1 && long_part() && meet_bindings_gauss_seidel(run)) return true;
    auto miss = [&](const LambdaRun& r, std::size_t m) {
      const double t = passing_at(r.sim.trace, points_[binding_[m]].s_m).t_s;
      return finite(t) ? std::abs(t - search_target_s(m)) : kInf;
    };
    auto within = [&](std::size_t m) { return miss(run, m) <= passing_tolerance_s(m); };
    auto worst = [&](const LambdaRun& r) {
      double w = 0.0;
      for (std::size_t m = 0; m < k; ++m) w = std::max(w, miss(r, m));
      return w;
    };
    // The cycles need not converge: a price moves its own point most, but the later ones by
    // seconds, and the passing times jump between neighbouring prices; traced on a hard random
    // journey, a cycle within 0.93 s of every target was followed by four ending 4-20 s away.
    // So the end of the cycle nearest every target is kept, the cycles stop after kStaleCycles
    // that come no nearer, and the joint Newton step (meet_bindings_exactly) starts from it.
    struct Snapshot {
      double worst_s;
      LambdaRun run;
      std::vector<double> before;
      double after, guess;
      bool floor;
    };
    std::optional<Snapshot> nearest;
    int stale = 0;
    const int cycles = k > 1 ? kMaxCycles : 1;
    for (int cycle = 0; cycle < cycles; ++cycle) {
      for (std::size_t m = 0; m < k; ++m) {
        if (k > 1 && within(m)) continue;
        if (!search_price(m, run)) return false;
      }
      bool all = true;
      for (std::size_t m = 0; m < k; ++m) all = all && within(m);
      if (all) return true;
      if (k == 1) continue;
      const double w = worst(run);
      if (!nearest || w < nearest->worst_s) {
        nearest = Snapshot{w, run, before_, lambda_after_, x_after_guess_, arrival_at_floor_};
        stale = 0;
      } else if (++stale == kStaleCycles) {
        break;
      }
    }
    if (nearest && worst(run) > nearest->worst_s) {
      run = std::move(nearest->run);
      before_ = std::move(nearest->before);
      lambda_after_ = nearest->after;
      x_after_guess_ = nearest->guess;
      arrival_at_floor_ = nearest->floor;
    }
    return true;
  }

  // The price searches stop within a few tenths (the running time is ragged on a grid); the
  // switch-point trims close the rest to kTrimTolerance_s.
  static constexpr double kArrivalTolerance_s = 0.25;
  static constexpr double kPassingTolerance_s = 0.25;
  static constexpr double kTrimTolerance_s = 0.5 * kZeroWidthTime_s;
  static constexpr int kInnerBudget = 40;
  // First steps (log price) of a price search: from a guess, and resumed near its root.
  static constexpr double kFirstLogPriceStep = 0.3;
  static constexpr double kRetryLogPriceStep = 0.01;
  static constexpr int kOuterBudget = 25;
  static constexpr int kMaxCycles = 6;    // of the searches for several binding points
  static constexpr int kStaleCycles = 2;  // cycles no nearer every target end them (meet_bindings)
  // meet_bindings_gauss_seidel: cycles, runs per search and its first log-price step.
  static constexpr int kGaussSeidelCycles = 8;
  static constexpr int kGaussSeidelBudget = 12;
  static constexpr double kGaussSeidelLogStep = 0.05;
  static constexpr double kGaussSeidelAccept_s = 1.0;
  static constexpr double kLongPart_m = 10000.0;  // see long_part
  static constexpr int kNewtonIterations = 12;    // Jacobians of newton_on_switches
  static constexpr int kBroydenIterations = 36;   // steps of newton_on_switches
  static constexpr double kNewtonStall = 0.9;     // see newton_on_switches
  static constexpr int kNewtonStalls = 2;
  // Newton solves of meet_bindings_exactly, each with the windows the one before missed held.
  static constexpr int kMissedWindowRounds = 4;
  static constexpr double kShortPhase_m = 5.0;  // see newton_without_short_phases
  static constexpr double kSplitPhase_m = 2.0;  // see newton_with_split_phases
  static constexpr double kInside_s = 0.1;
  static constexpr double kInsidePerStretch = 1e-3;  // of the stretch's seconds (inside_s)
  static constexpr double kSearchStep_m = 0.5;       // re-simulation step of a search's evaluation
  static constexpr double kMovingEndTrim_s = 5.0;
  // RK4 step of the cruise polish's simplex runs on a part that ends moving (its result is
  // met at the engine's fine step): 5 m halves the polish of the 48.5 km GPOPS-II case against
  // 1 m for the same energy to 0.002 % (docs/performance.md).
  static constexpr double kPolishPriceStep_m = 5.0;
  // What "exactly" means for a window of zero width (docs/ttobench.md).
  static constexpr double kExactTime_s = kZeroWidthTime_s;
  static constexpr double kExactSpeed_ms = kZeroWidthSpeed_ms;

  const SectionEngine& engine_;
  StartState start_;
  EndCheck end_;
  double target_s_;
  double earliest_arrival_s_;
  // The part's latest arrival lies beyond target_s_ (the slowest run the grid solves reliably):
  // any arrival from earliest_arrival_s_ to target_s_ is inside the window.
  bool arrival_free_ = false;
  std::vector<PartPoint> points_;
  const std::vector<TimingWindow>& windows_;
  const TimingJourneyOptions& options_;
  bool bands_on_both_stages_;
  std::vector<SpeedBand> bands_;
  std::vector<std::string> notes_;
  // The binding passing points (indices into points_, in order along the part), the bound each
  // meets and the price of the stretch ending at it; lambda_after_ after the last of them.
  bool arrival_at_floor_ = false;  // the last arrival search: even its lowest price is early
  bool exact_ = false;             // meet_bindings_exactly put every binding point at its bound
  std::vector<int> binding_;
  std::vector<bool> inactive_;  // per binding point (see inactive())
  std::vector<double> bound_s_;
  std::vector<double> before_;
  double lambda_after_ = 0.0;
  double x_after_guess_ = std::log(3e5);
  int evaluations_ = 0;
};

// +1 when a run passing p at t_s meets its latest bound (within tol_s or past it), -1 its
// earliest, 0 neither.
int time_side(const PartPoint& p, double t_s, double tol_s) {
  if (finite(p.latest_s) && t_s >= p.latest_s - tol_s) return 1;
  if (finite(p.earliest_s) && t_s <= p.earliest_s + tol_s) return -1;
  return 0;
}

}  // namespace

PartOutcome solve_part(const SectionEngine& engine, const StartState& start, const EndCheck& end,
                       double target_s, double earliest_arrival_s, std::vector<PartPoint> points,
                       const std::vector<TimingWindow>& windows,
                       const TimingJourneyOptions& options, bool arrival_free, bool by_labels) {
  // Speed windows between stages are banded on the sweep's transitions first (the window
  // itself); when that search ends without a run meeting every window, on the nodes of the
  // stages either side (stricter, PartSolver::bands_at), and that run is kept if it does.
  struct Attempt {
    PartOutcome out;
    bool banded_transitions = false;  // a window was banded on the sweep's transitions
    // The search met the windows and every one holds on the run's re-simulation.
    bool kept() const { return out.met && out.holds; }
  };
  auto attempt = [&](bool both_stages) {
    PartSolver solver(engine, start, end, target_s, earliest_arrival_s, points, windows, options,
                      both_stages, arrival_free);
    Attempt a;
    PartOutcome& out = a.out;
    out.run = solver.solve(&out.met);
    out.holds = solver.every_window_holds(out.run);
    a.banded_transitions = solver.banded_transitions();
    out.evaluations = solver.evaluations();
    out.points = solver.points();
    out.notes = solver.notes();
    const int n = static_cast<int>(out.points.size());
    for (int k = 0; k <= n; ++k) {
      out.stretch_lambda_J_per_s.push_back(solver.stretch_price(k));
      if (k < n) out.binding_sign.push_back(solver.binding_sign(k));
    }
    out.binding_slack_s = solver.binding_slack_s();
    return a;
  };
  // Whether every window of the part holds on a run found outside the price search.
  auto holds_on = [&](const LambdaRun& run) {
    return PartSolver(engine, start, end, target_s, earliest_arrival_s, points, windows, options,
                      false, arrival_free)
        .every_window_holds(run);
  };
  // The passing points a descent on the run's switches holds (dp/timing_switch_descent.hpp):
  // a zero-width time or speed at its value, a window the run meets at a bound at the run's
  // own value there (so the descent keeps every window the run meets; the part's check of
  // every window then decides).
  auto held_on = [&](const LambdaRun& run) {
    const double tol_t = options.time_tolerance_s;
    const double tol_v = units::kmh_to_ms(options.speed_tolerance_kmh);
    std::vector<HeldPassing> held;
    for (const PartPoint& p : points) {
      const TimingWindow& w = windows[p.index];
      const Passing at = passing_at(run.sim.trace, p.s_m);
      HeldPassing h{p.s_m, NAN, NAN};
      if (finite(p.earliest_s) && p.earliest_s == p.latest_s) {
        h.time_s = p.earliest_s;
      } else if (time_side(p, at.t_s, tol_t) != 0) {
        h.time_s = at.t_s;
      }
      if (finite(w.min_speed_ms) && w.min_speed_ms == w.max_speed_ms) {
        h.speed_ms = w.min_speed_ms;
      } else if ((finite(w.max_speed_ms) && at.v_ms >= w.max_speed_ms - tol_v) ||
                 (finite(w.min_speed_ms) && at.v_ms <= w.min_speed_ms + tol_v)) {
        h.speed_ms = at.v_ms;
      }
      if (finite(h.time_s) || finite(h.speed_ms)) held.push_back(h);
    }
    return held;
  };
  // A part whose every run arrives before its earliest arrival, or that asks for a time beyond
  // the slowest run the grid solves (a fast moving start, a late stop or a high end speed): its
  // energy rises with its time there, so the run of dp/timing_family_run.hpp at the earliest
  // arrival is taken when every window of the part holds on it.
  // (fast: the search's run that arrives too early, or null; the slow run follows it up to the
  // part's last passing point.)
  auto slow = [&](const PartOutcome* fast) -> std::optional<PartOutcome> {
    if (!finite(earliest_arrival_s)) return std::nullopt;
    const bool lead = fast && !points.empty();
    int simulations = 0;
    std::optional<LambdaRun> run =
        family_run(engine, start, end, earliest_arrival_s,
                   lead ? fast->run.program : physics::ControlProgram{},
                   lead ? points.back().s_m : 0.0, FamilySet::Slowing, &simulations);
    if (!run || !holds_on(*run)) return std::nullopt;
    PartOutcome out;
    out.evaluations = fast ? fast->evaluations : 0;
    out.run = std::move(*run);
    out.met = out.holds = true;
    out.points = points;
    out.stretch_lambda_J_per_s.assign(points.size() + 1, NAN);
    out.binding_sign.assign(points.size(), 0);
    out.notes.push_back(format_text(
        "a part needs a run slower than any time price gives (its energy rises with its time "
        "there): it slows down by braking and coasting and then runs to its end, arriving %.3f s "
        "after its departure (%d simulations; feasible, possibly not the least energy)",
        out.run.sim.running_time_s, simulations));
    return out;
  };
  auto too_fast = [&](const PartOutcome& o) {
    return !o.holds && end.reaches_end(o.run.sim) &&
           o.run.sim.running_time_s < earliest_arrival_s - options.time_tolerance_s;
  };
  // A part that ends at one speed (a point pinning the state, or a zero-width end window): its
  // grid run, moved onto that speed on the simulator, can cost more than a run of a few phases
  // after its last passing point (dp/timing_family_run.hpp); the cheaper is kept where every
  // window holds on it. Parts longer than kFamilyReach_m are left as they are.
  auto polish_one_speed_end = [&](PartOutcome& o) {
    if (!end.moving || end.min_ms != end.max_ms || !o.holds ||
        engine.route().length_m() > kFamilyReach_m) {
      return;
    }
    const double from_m = points.empty() ? 0.0 : points.back().s_m;
    const double grid_cost_J = o.run.cost_J;
    int simulations = 0;
    bool replaced = false;
    // Each shape, the grid's (its phases) and the families' (the few phases a level track
    // asks for), and each grown by one phase, descended on its switches
    // (dp/timing_switch_descent.hpp); then the cheapest grown by one more phase and descended
    // again. The descent cannot add a phase, and a run may want traction, a hold, a coast,
    // traction again and a coast: the phases grown are a coast or traction for the last few
    // metres and a hold before the end of the first traction. The cheapest run where every
    // window holds is kept.
    const double end_phase_m = engine.route().length_m() - kEndPhase_m;
    auto grown = [&](const LambdaRun& shape) {
      const physics::ControlProgram& p = shape.program;
      std::vector<LambdaRun> out;
      auto add = [&](physics::ControlProgram program) {
        LambdaRun variant = shape;
        variant.program = std::move(program);
        variant.sim = engine.resimulate(variant.program, start, shape.sim);
        ++simulations;
        out.push_back(std::move(variant));
      };
      if (!p.empty() && p.back().from_m < end_phase_m - kEndPhase_m && end_phase_m > from_m) {
        for (const physics::Control c : {physics::Control::Coast, physics::Control::MaxTraction}) {
          if (p.back().control == c) continue;
          physics::ControlProgram q = p;
          q.push_back({end_phase_m, c});
          add(std::move(q));
        }
      }
      for (std::size_t j = 1; j < p.size(); ++j) {
        if (p[j - 1].control != physics::Control::MaxTraction || !(p[j].from_m > from_m)) continue;
        if (p[j].control != physics::Control::Hold &&
            p[j].from_m - kEndPhase_m > std::max(p[j - 1].from_m, from_m) + kEndPhase_m) {
          physics::ControlProgram q = p;
          q.insert(q.begin() + static_cast<std::ptrdiff_t>(j),
                   {p[j].from_m - kEndPhase_m, physics::Control::Hold});
          add(std::move(q));
        }
        break;
      }
      return out;
    };
    // Descends each shape; keeps the cheapest run that holds every window.
    int budget = options.descend_on_switches ? kDescentSimulations : 0;
    auto descend_all = [&](const std::vector<LambdaRun>& shapes) {
      for (const LambdaRun& shape : shapes) {
        SwitchDescentOptions descent_options;
        descent_options.max_simulations = std::min(descent_options.max_simulations, budget);
        SwitchDescentResult descent;
        if (descent_options.max_simulations > 0) {
          descent = descend_switches(engine, start, end, o.run.sim.running_time_s, shape, 0.0,
                                     descent_options, held_on(shape));
        }
        simulations += descent.simulations;
        budget -= descent.simulations;
        const LambdaRun* descended = descent.run ? &*descent.run : nullptr;
        for (const LambdaRun* run : {&shape, descended}) {
          if (run && run->cost_J < (1.0 - kDescentGain) * o.run.cost_J && holds_on(*run)) {
            o.run = *run;
            replaced = true;
          }
        }
      }
    };
    std::vector<LambdaRun> shapes = {o.run};
    if (std::optional<LambdaRun> run =
            family_run(engine, start, end, o.run.sim.running_time_s, o.run.program, from_m,
                       FamilySet::Any, &simulations)) {
      shapes.push_back(std::move(*run));
    }
    for (std::size_t k = 0, n = shapes.size(); k < n; ++k) {
      for (LambdaRun& variant : grown(shapes[k])) shapes.push_back(std::move(variant));
    }
    descend_all(shapes);
    descend_all(grown(o.run));
    if (!replaced) return;
    // The prices were those of the grid's run, which is no longer the part's: they are
    // cleared, and the replacement is said. (The passing points the run met at a bound are
    // held there, so their binding sides stand.) A multiplier of the new run's time equation,
    // balanced against its cost gradient, was tried and not kept: where the descent ends at a
    // kink it was twice the slope of the least energy in time.
    o.stretch_lambda_J_per_s.assign(o.stretch_lambda_J_per_s.size(), NAN);
    o.notes.push_back(format_text(
        "a part that ends at one speed has its run re-shaped (runs of a few phases after its "
        "last passing point, a descent on its switches), %.1f kJ cheaper than the run its "
        "search found (%d simulations; feasible, possibly not the least energy; its time prices "
        "are not reported)",
        (grid_cost_J - o.run.cost_J) / 1e3, simulations));
  };
  // A part that ends at a stop: its run descended on its switches at its own arrival time,
  // holding its passing points (dp/timing_switch_descent.hpp), where the grid's run, even
  // polished, is a step away from the continuous optimum (a descent into a lower limit).
  auto descend_stop_end = [&](PartOutcome& o) {
    if (end.moving || !o.holds || !options.descend_on_switches ||
        engine.route().length_m() > kStopDescentReach_m) {
      return;
    }
    SwitchDescentOptions descent_options;
    descent_options.max_simulations = kStopDescentSimulations;
    const SwitchDescentResult descent = descend_switches(
        engine, start, end, o.run.sim.running_time_s, o.run, 0.0, descent_options, held_on(o.run));
    if (!descent.run || !(descent.run->cost_J < (1.0 - kDescentGain) * o.run.cost_J) ||
        !holds_on(*descent.run)) {
      return;
    }
    const double saved_J = o.run.cost_J - descent.run->cost_J;
    o.run = *descent.run;
    // The prices are cleared, as above.
    o.stretch_lambda_J_per_s.assign(o.stretch_lambda_J_per_s.size(), NAN);
    o.notes.push_back(format_text(
        "a part that ends at a stop has its run descended on its switches, %.1f kJ cheaper than "
        "the run its search found (%d simulations; feasible, possibly not the least energy; its "
        "time prices are not reported)",
        saved_J / 1e3, descent.simulations));
  };
  // Every run a part returns, the search's or a slow run, is polished and descended.
  auto finished = [&](PartOutcome o) {
    polish_one_speed_end(o);
    descend_stop_end(o);
    return o;
  };
  // Which side of each passing point's window the run meets (+1 latest, -1 earliest, 0
  // neither), for a run found outside the price search.
  auto sides_of = [&](const LambdaRun& run) {
    std::vector<int> sides;
    for (const PartPoint& p : points) {
      sides.push_back(time_side(p, passing_at(run.sim.trace, p.s_m).t_s, options.time_tolerance_s));
    }
    return sides;
  };
  // The last resort (dp/timing_label_search.hpp): the label search's run, moved onto its
  // windows where its re-simulation misses one (each passing time by one switch before it,
  // repair_passing_times; a zero-width end by the descent's Newton steps on the switches after
  // the last passing point), then finished as any run.
  if (by_labels) {
    PartOutcome o;
    o.points = points;
    o.stretch_lambda_J_per_s.assign(points.size() + 1, NAN);
    o.binding_sign.assign(points.size(), 0);
    std::vector<LabelWindow> label_windows;
    for (const PartPoint& p : points) {
      const TimingWindow& w = windows[p.index];
      label_windows.push_back({p.s_m, p.earliest_s, p.latest_s, w.min_speed_ms, w.max_speed_ms});
    }
    const double earliest = finite(earliest_arrival_s) ? earliest_arrival_s : 0.0;
    // Its buckets decide which runs it keeps, and a run of the coarser buckets can be lost in
    // the finer ones' (or the other way round): each bucket size in turn, the first run that
    // is moved onto every window kept.
    std::optional<LambdaRun> kept_run;
    LabelSearchResult found;
    for (const double bucket_s : kLabelTimeBuckets_s) {
      LabelSearchOptions label_options;
      label_options.time_bucket_s = bucket_s;
      found = label_search(engine, start, end, earliest, target_s, label_windows, label_options,
                           options.progress);
      o.evaluations += found.stages;
      if (!found.run) continue;
      LambdaRun run = *found.run;
      if (!holds_on(run)) {
        int simulations = 0;
        repair_passing_times(engine, start, run, label_windows, &simulations);
        o.evaluations += simulations;
      }
      if (!holds_on(run) && earliest <= target_s) {
        // The end (a zero-width arrival or end speed) by the descent's Newton steps on the
        // switches after the last passing point, which leave the points where they are.
        SwitchDescentOptions restore_only;
        restore_only.max_rounds = 1;
        const SwitchDescentResult moved = descend_switches(
            engine, start, end, std::clamp(run.sim.running_time_s, earliest, target_s), run,
            points.empty() ? 0.0 : points.back().s_m, restore_only);
        o.evaluations += moved.simulations;
        if (moved.run) run = *moved.run;
      }
      if (holds_on(run)) {
        kept_run = std::move(run);
        break;
      }
    }
    if (!kept_run) {
      o.notes.push_back(format_text(
          "the label search found no run that meets the part's windows (%ld labels on %d "
          "stages%s)",
          found.labels, found.stages, found.out_of_budget ? ", stopped at its budget" : ""));
      return o;
    }
    o.run = std::move(*kept_run);
    o.met = o.holds = true;
    o.notes.push_back(
        format_text("the part's price searches missed a window; its run is the time-expanded label "
                    "search's (%ld labels on %d stages), moved onto its windows on the simulator "
                    "(feasible, possibly not the least energy; its time prices are not reported)",
                    found.labels, found.stages));
    o = finished(std::move(o));
    o.binding_sign = sides_of(o.run);
    return o;
  }
  std::optional<Attempt> first;
  try {
    first = attempt(false);
  } catch (const LongTimeError& e) {
    // (A part whose earliest arrival the grid reaches is searched with a free arrival by the
    // caller.)
    if (e.maximum_s() >= earliest_arrival_s) throw;
    if (std::optional<PartOutcome> o = slow(nullptr)) return finished(std::move(*o));
    throw;
  }
  PartOutcome* kept = &first->out;
  Attempt strict;
  if (!first->kept() && first->banded_transitions) {
    strict = attempt(true);
    const int evaluations = first->out.evaluations + strict.out.evaluations;
    if (strict.kept()) kept = &strict.out;
    kept->evaluations = evaluations;
  }
  if (too_fast(*kept)) {
    if (std::optional<PartOutcome> o = slow(kept)) return finished(std::move(*o));
  }
  return finished(std::move(*kept));
}

}  // namespace ecorail::dp::timing
